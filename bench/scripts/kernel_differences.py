#!/usr/bin/env python3
"""The largest relative difference between kernel forms on Q_s, A_s and t_peak.

Runs the regression suite's interacting entries, the stand-in P3.09N at the fit's trial point
whose slips overload a neighbour, and `bench interacting` at N = 2,400 (where the AVX2 / AVX-512
forms keep G's single-precision copy and the portable one does not) under each kernel form this
CPU has (tests/shell/kernel_variant.sh), and writes, per run and quantity, each form's value and
the largest relative difference between forms.
    bench/scripts/kernel_differences.py [OUT_CSV]   (default results/bench/kernel_differences.csv)
Environment: ASPERITY (default build/asperity); KERNEL_DIFFERENCES_BENCH=0 leaves out the bench run.
"""
import csv
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BIN = os.environ.get("ASPERITY", os.path.join(ROOT, "build", "asperity"))
VARIANT = os.path.join(ROOT, "tests", "shell", "kernel_variant.sh")
RUNS = [
    ("P0.98N_interacting", "scenes/paper/P0.98N.yaml", ["model.interactions=elastic", "stop.time=4"]),
    ("P0.98N_interacting_cutoff", "scenes/paper/P0.98N.yaml",
     ["model.interactions=elastic", "model.interaction_cutoff=5e-4", "stop.time=4"]),
    ("P0.98N_interacting_always", "scenes/paper/P0.98N.yaml",
     ["model.interactions=elastic", "model.area_law=always", "stop.time=3"]),
    ("P4.00N_interacting_first_peak", "scenes/paper/P4.00N.yaml",
     ["model.interactions=elastic", "stop.at_first_peak=true"]),
    ("P3.09N_overload_trial", "scenes/paper/P3.09N.yaml",
     ["model.interactions=elastic", "model.alpha_b=7.07107e-16", "model.epsilon=0.581667",
      "model.eta=94.8683", "stop.at_first_peak=true", "stop.time=13"]),
]
QUANTITIES = ["Q_s", "A_s", "t_peak"]


def summary_values(path):
    values = {}
    with open(path) as f:
        for line in f:
            key, _, rest = line.partition(":")
            if key.strip() in QUANTITIES and rest.strip():
                values[key.strip()] = float(rest.split("#")[0].strip())
    return values


def run(form, args, tmp):
    p = subprocess.run([VARIANT, form, BIN] + args, cwd=ROOT, capture_output=True, text=True)
    if p.returncode == 77:
        return None
    if p.returncode != 0:
        sys.exit(f"kernel_differences: {form}: {' '.join(args)} failed:\n{p.stdout}{p.stderr}")
    return True


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "results", "bench", "kernel_differences.csv")
    values = {}  # (run, quantity) -> {form: value}
    forms = []
    with tempfile.TemporaryDirectory() as tmp:
        for form in ["portable", "avx2", "avx512"]:
            d = os.path.join(tmp, form)
            if run(form, ["run", RUNS[0][1], "-q", "-o", os.path.join(d, "probe"), "--set", "stop.time=0.01"], tmp) is None:
                print(f"{form}: skipped (this CPU lacks it)")
                continue
            forms.append(form)
            for name, scene, sets in RUNS:
                args = ["run", scene, "-q", "-o", os.path.join(d, name)]
                for s in sets:
                    args += ["--set", s]
                run(form, args, tmp)
                for q, v in summary_values(os.path.join(d, name, "summary.yaml")).items():
                    values.setdefault((name, q), {})[form] = v
            if os.environ.get("KERNEL_DIFFERENCES_BENCH", "1") == "0":
                print(f"{form}: done (no bench run)")
                continue
            run(form, ["bench", "-j", str(os.cpu_count()), "interacting", "--sizes", "2400", "-q", "-o",
                       os.path.join(d, "bench")], tmp)
            with open(os.path.join(d, "bench", "interacting.csv")) as f:
                for row in csv.DictReader(f):
                    if row["what"] != "first_peak":
                        continue
                    for q, col in (("Q_s", "Q_s_N"), ("A_s", "A_s_m2"), ("t_peak", "t_peak_s")):
                        values.setdefault(("bench_N2400_first_peak", q), {})[form] = float(row[col])
            print(f"{form}: done")
    rows = []
    worst = {q: 0.0 for q in QUANTITIES}
    for (name, q), by_form in values.items():
        vs = [by_form[f] for f in forms if f in by_form]
        ref = max(abs(v) for v in vs)
        diff = (max(vs) - min(vs)) / ref if ref > 0 else 0.0
        worst[q] = max(worst[q], diff)
        rows.append([name, q] + [repr(by_form.get(f, float("nan"))) for f in forms] + [f"{diff:.3g}"])
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    with open(out + ".tmp", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run", "quantity"] + forms + ["max_relative_difference"])
        w.writerows(rows)
    os.replace(out + ".tmp", out)
    print("largest relative difference between forms (" + ", ".join(forms) + "): "
          + ", ".join(f"{q} {worst[q]:.3g}" for q in QUANTITIES))
    print(f"-> {out}")


if __name__ == "__main__":
    main()
