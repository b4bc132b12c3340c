#!/usr/bin/env python3
"""The coverage of the joint fit's error bars (scripts/coverage.sh): per noise seed, each
parameter's fitted value, its Hessian σ and z = (value − truth)/σ; then per parameter the mean and
rms of z over the certified fits (rms z ≈ 1: the σ are the scatter's; > 1: they are too small).
    coverage_table.py WORK OUT.csv [MODEL]   (WORK holds one fit folder out_SEED per seed; MODEL:
    independent, the default, or interacting, whose fit also frees the position scale)"""
import csv
import math
import re
import sys
from pathlib import Path

TRUTH = {"model.alpha_b": 0.7e-15, "model.epsilon": 0.9, "model.eta": 100.0}  # the recipes' set:
POSITION_SCALE = {"model.position_scale": 1.0}  # the scene's, free in the interacting fit


def read_fit(path, truth):
    """converged and {parameter: (value, sigma)} of fit.yaml's one fit (its flow-map lines)."""
    text = path.read_text(encoding="utf-8")
    converged = re.search(r"^    converged: (\w+)", text, re.M).group(1)
    values = {}
    for key in truth:
        m = re.search(r'^        "%s": \{value: ([^,]+), step: [^,]+, sigma: ([^,]+),' % re.escape(key), text, re.M)
        if m:
            values[key] = (float(m.group(1)), float(m.group(2)))
    return converged, values


def main():
    work, out = Path(sys.argv[1]), Path(sys.argv[2])
    model = sys.argv[3] if len(sys.argv) > 3 else "independent"
    truth_of = dict(TRUTH, **POSITION_SCALE) if model == "interacting" else TRUTH
    rows, z = [], {k: [] for k in truth_of}
    for folder in sorted(work.glob("out_*"), key=lambda p: int(p.name[4:])):
        converged, values = read_fit(folder / "fit.yaml", truth_of)
        row = {"seed": folder.name[4:], "converged": converged}
        for key, truth in truth_of.items():
            value, sigma = values.get(key, (math.nan, math.nan))
            zi = (value - truth) / sigma
            row[key] = repr(value)
            row[key + "_sigma"] = repr(sigma)
            row[key + "_z"] = "%.3f" % zi
            if converged == "yes" and math.isfinite(zi):
                z[key].append(zi)
        rows.append(row)
    with open(out, "w", newline="") as f:
        f.write("# SYNTHETIC experiments (examples/recovery/recipe_light_%s.yaml at each seed), "
                "fitted by fit_%s.yaml: scripts/coverage.sh\n" % (model, model))
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    for key, v in z.items():
        if v:
            print("%s: %d certified fits, mean z %.2f, rms z %.2f, largest |z| %.2f"
                  % (key, len(v), sum(v) / len(v), math.sqrt(sum(x * x for x in v) / len(v)), max(map(abs, v))))
        else:
            print("%s: no certified fit: no evidence" % key)


if __name__ == "__main__":
    main()
