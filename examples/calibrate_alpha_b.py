#!/usr/bin/env python3
"""Calibrates alpha_b for one STAND-IN experiment with the paper's method (the quadratic
coefficient of A(Q) on the loading branch, matched to the measured one) and draws the measured
and the calibrated model's A(Q).

    PYTHONPATH=build/python python3 examples/calibrate_alpha_b.py [--load P1.52N] [--out alpha_b_P1.52N.png]

The data are the project's STAND-INS (data/standin/, generated, not measurements): the figure
says so. Never overwrites an existing file.
"""
import argparse
import os
import pathlib
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

import asperity  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--load", default="P1.52N", help="stand-in experiment (scenes/paper/<load>.yaml)")
    ap.add_argument("--out", default=None, help="figure file (default alpha_b_<load>.png here)")
    ap.add_argument("--quick", action="store_true", help="a coarser fit (for tests)")
    a = ap.parse_args()
    scene_file = ROOT / "scenes" / "paper" / f"{a.load}.yaml"
    out = pathlib.Path(a.out or f"alpha_b_{a.load}.png")
    if out.exists():
        sys.exit(f"{out}: exists; not overwriting it (choose another --out)")

    # The fit: one experiment, alpha_b on a log scale, BOBYQA (as fits/paper_alpha_b.yaml).
    with tempfile.TemporaryDirectory() as tmp:
        fit_file = pathlib.Path(tmp) / "fit.yaml"
        fit_file.write_text(
            f"name: alpha_b_{a.load}\n"
            "objective: quadratic_alpha\n"
            f"experiments: [{scene_file}]\n"
            "parameters: {model.alpha_b: {lo: 0.1e-15, hi: 5.0e-15, start: 0.725e-15, scale: log}}\n"
            "optimizer: {algorithm: LN_BOBYQA, xtol_rel: " + ("1.0e-3" if a.quick else "1.0e-4") +
            ", max_evaluations: " + ("20" if a.quick else "60") + ", initial_step: 0.05}\n")
        result = asperity.fit(fit_file, threads=1, profile=False, error_bars=False)  # the optimum only
    (fit,) = result["fits"]
    if fit["failure"]:
        sys.exit(f"fit failed: {fit['failure']}")
    alpha_b = fit["best"]["model.alpha_b"]
    print(f"{a.load}: alpha_b = {alpha_b:.6g} m^5/N^2 after {fit['evaluations']} evaluations "
          f"({fit['stop_reason']}), objective {fit['objective']:.3g}")

    # The calibrated model up to its first peak, and the measured curve.
    scene = asperity.load_scene(scene_file, {"model.alpha_b": alpha_b, "stop.at_first_peak": True})
    run = asperity.run(scene)
    s, measured = run.series, asperity.measured(scene)
    loading = s["t"] <= run.summary["t_peak"]
    mm2 = 1e6  # m² → mm²
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.plot(measured["Q"], measured["A"] * mm2, "o", ms=3, color="0.35", label="stand-in 'measured' A(Q)")
    ax.plot(s["Q"][loading], s["A"][loading] * mm2, "-", color="C3",
            label=f"model, $\\alpha_b$ = {alpha_b:.3g} m$^5$/N$^2$")
    ax.set_xlabel("tangential force Q (N)")
    ax.set_ylabel("real contact area A (mm$^2$)")
    ax.set_title(f"{a.load}: calibrated $\\alpha_b$ (STAND-IN data, not measurements)", fontsize=10)
    ax.legend(frameon=False, fontsize=9)
    fig.tight_layout()
    # Exclusive create: a file that appeared meanwhile is not replaced.
    with open(out, "xb") as f:
        fig.savefig(f, format=out.suffix.lstrip(".") or "png", dpi=150)
    print(f"-> {out}")


if __name__ == "__main__":
    main()
