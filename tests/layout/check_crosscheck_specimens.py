#!/usr/bin/env python3
"""One source for docs/validation.md's table of the cross-check over three
specimens: each run's dilations at 6 mm, their mean and standard deviation,
and the means and standard deviations of the first peak and of the mean
tau/sigma after 2.3 mm are those of docs/img/crosscheck_specimens.csv
(written by assets/crosscheck/liggghts/specimens.py).
  tests/layout/check_crosscheck_specimens.py [REPO_ROOT]"""
import csv
import math
import os
import sys

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
with open(os.path.join(root, "docs/img/crosscheck_specimens.csv")) as f:
    rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
doc = open(os.path.join(root, "docs/validation.md"), encoding="utf-8").read()
section = doc[doc.index("### The volume over three specimens"):]
names = {"LIGGGHTS epsd2": "LIGGGHTS `epsd2`", "SimSols constant_torque": "SimSols `constant_torque`",
         "SimSols spring_dashpot": "SimSols model C"}


def mean_sd(v):
    m = sum(v) / len(v)
    return m, math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1))


def signed(x, digits=3):
    return ("+" if x >= 0 else "−") + f"{abs(x):.{digits}f}"


bad = []
for run, label in names.items():
    mine = sorted((r for r in rows if r["run"] == run), key=lambda r: int(r["seed"]))
    line = next((l for l in section.splitlines() if l.startswith(f"| {label} |")), None)
    if line is None or len(mine) != 3:
        bad.append(f"{label}: no row in the docs, or not 3 specimens in the CSV")
        continue
    cells = [c.strip() for c in line.strip("|").split("|")]
    dil = [float(r["dilation_end_mm"]) for r in mine]
    want = " / ".join(signed(x) for x in dil)
    if cells[1] != want:
        bad.append(f"{label}: dilations '{cells[1]}', the CSV gives '{want}'")
    m, sd = mean_sd(dil)
    if cells[2] != f"{signed(m)} ± {sd:.3f}":
        bad.append(f"{label}: mean '{cells[2]}', the CSV gives '{signed(m)} ± {sd:.3f}'")
    for col, key in ((3, "first_peak"), (4, "window_mean")):
        m, sd = mean_sd([float(r[key]) for r in mine])
        if cells[col] != f"{m:.3f} ± {sd:.3f}":
            bad.append(f"{label}: {key} '{cells[col]}', the CSV gives '{m:.3f} ± {sd:.3f}'")
for b in bad:
    print("check_crosscheck_specimens:", b)
if not bad:
    print(f"check_crosscheck_specimens: the {len(names)} rows agree with the CSV")
sys.exit(1 if bad else 0)
