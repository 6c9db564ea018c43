#!/usr/bin/env python3
"""One source for docs/size-study.md's tables: each table under a
`<!-- size_NAME: ... -->` marker holds, row by row, the numbers of
docs/img/size_NAME_summary.csv (scale, L/d, beads, specimens, each
headline's mean ± interval, wall time per test) as `simsols study size`
formats them (app/experiment/size_study.cpp), and that CSV's means and
95 % Student intervals are those of docs/img/size_NAME_tests.csv's tests;
docs/accuracy.md's residuals of the fixed-thickness box are that study's.
  tests/layout/check_size_study_tables.py [REPO_ROOT]"""
import csv
import glob
import os
import re
import sys

from ensemble_stats import mean_ci

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
doc = open(os.path.join(root, "docs/size-study.md"), encoding="utf-8").read()
bad = []


def g3(v):
    """C's %.3g"""
    s = "%.3g" % v
    return s


def table_of(name):
    marker = f"<!-- size_{name}:"
    if marker not in doc:
        return None
    lines = doc[doc.index(marker):].splitlines()[1:]
    rows = []
    for line in lines[2:]:
        if not line.startswith("|"):
            break
        rows.append([c.strip() for c in line.strip("|").split("|")])
    return rows


def csv_rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


names = sorted(os.path.basename(p)[5:-12] for p in glob.glob(os.path.join(root, "docs/img/size_*_summary.csv")))
if not names:
    bad.append("no docs/img/size_*_summary.csv")
for name in names:
    summary = csv_rows(os.path.join(root, f"docs/img/size_{name}_summary.csv"))
    keys = [k for k in summary[0] if k.endswith("_ci95")]
    heads = [k[:-5] for k in keys]
    table = table_of(name)
    if table is None:
        bad.append(f"docs/size-study.md has no table marked <!-- size_{name}: ... -->")
        continue
    if len(table) != len(summary):
        bad.append(f"size_{name}: {len(table)} rows in the docs, {len(summary)} in the CSV")
    for got, r in zip(table, summary):
        want = [f"{float(r['scale']):g}", f"{float(r['size_ratio_L_over_d']):.1f}", r["beads"], r["specimens"]]
        want += [f"{g3(float(r[h]))} ± {g3(float(r[h + '_ci95']))}" for h in heads]
        want.append(f"{float(r['wall_s_per_test']):.0f}")
        if got != want:
            bad.append(f"size_{name}: the docs say\n  {got}\nthe CSV gives\n  {want}")
    tests = csv_rows(os.path.join(root, f"docs/img/size_{name}_tests.csv"))
    for r in summary:
        group = [t for t in tests if float(t["scale"]) == float(r["scale"])]
        if len(group) != int(r["specimens"]):
            bad.append(f"size_{name} x{r['scale']}: {len(group)} tests, {r['specimens']} specimens")
            continue
        for h in heads:
            v = [float(t[h]) for t in group]
            n = len(v)
            m, half = mean_ci(v)
            if abs(m - float(r[h])) > 1e-4 * max(1, abs(m)) or (
                    n > 1 and abs(half - float(r[h + "_ci95"])) > 1e-4 * max(1, half)):
                bad.append(f"size_{name} x{r['scale']} {h}: tests give {m:.6g} ± {half:.6g}, "
                           f"the summary {r[h]} ± {r[h + '_ci95']}")

# docs/accuracy.md quotes the fixed-thickness residuals ("Why 1 296 beads")
fixed = csv_rows(os.path.join(root, "docs/img/size_poured_fixed_summary.csv"))
quote = ", ".join(f"{float(r['residual_friction_angle_deg']):.1f}" for r in fixed[:-1])
quote += f" and {float(fixed[-1]['residual_friction_angle_deg']):.1f}°"
accuracy = open(os.path.join(root, "docs/accuracy.md"), encoding="utf-8").read()
if quote not in " ".join(accuracy.split()):
    bad.append(f"docs/accuracy.md should quote the fixed-thickness residuals as '{quote}'")

for b in bad:
    print(b)
sys.exit(1 if bad else 0)
