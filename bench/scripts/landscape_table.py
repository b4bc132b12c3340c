#!/usr/bin/env python3
"""One table of the objective's 1-D profiles through a synthetic experiment's truth, one column
per Q(t) score (scripts/landscape.sh): parameter, factor (value / truth), value, J per score.
    landscape_table.py WORK OUT.csv   (WORK holds one fit folder per score)"""
import csv
import sys
from pathlib import Path

SCORES = ["pointwise", "loading_and_cycles", "loading_and_peaks"]
PROFILES = {"model.alpha_b": "profile.csv", "model.epsilon": "profile_model.epsilon.csv",
            "model.eta": "profile_model.eta.csv"}


def read_profile(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return {(r["factor"], r["value"]): r["objective"] for r in rows}


def main():
    work, out = Path(sys.argv[1]), Path(sys.argv[2])
    lines = []
    for parameter, name in PROFILES.items():
        columns = [read_profile(work / score / name) for score in SCORES]
        for key in columns[0]:
            lines.append([parameter, key[0], key[1]] + [c.get(key, "") for c in columns])
    with open(out, "w", newline="") as f:
        f.write("# SYNTHETIC experiment (examples/landscape/recipe.yaml): the joint objective J through its truth,\n"
                "# one parameter at a time (scripts/landscape.sh). J: chi-square, area_and_force; empty: outside the box.\n")
        w = csv.writer(f)
        w.writerow(["parameter", "factor", "value"] + ["J_" + s for s in SCORES])
        w.writerows(lines)


if __name__ == "__main__":
    main()
