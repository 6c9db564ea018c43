#!/usr/bin/env python3
"""One source for docs/oedometer.md's "Past the elastic range": each row of
its table is the shipped docs/img/oedometer_loose_summary.csv (the runs'
summary.txt values), and the Karlsruhe fine sand figures it quotes (plastic
share 25 -> 407 -> 25 kPa, Cc over 100-407 kPa, Cs on unloading to 25 kPa,
their ranges over the twelve tests) are computed here from the original
data in assets/validation/karlsruhe_fine_sand_oedometer.csv.
  tests/layout/check_oedometer_tables.py [REPO_ROOT]"""
import csv
import math
import os
import sys
from collections import defaultdict

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
doc = open(os.path.join(root, "docs/oedometer.md"), encoding="utf-8").read()
section = doc[doc.index("## Past the elastic range"):]
bad = []

for r in csv.DictReader(open(os.path.join(root, "docs/img/oedometer_loose_summary.csv"))):
    row = (f"| {r['scene']} | {r['seed']} | {r['seated_void_ratio']} | {r['void_ratio_at_largest']} | "
           f"{r['compression_index_cc']} | {r['swelling_index_cs']} | {r['plastic_share']} | "
           f"{r['k0_normally_consolidated']} | {r['implied_friction_angle_deg']} | "
           f"{r['k0_after_unloading']} ({r['ocr_after_unloading']}) | "
           f"{r['mayne_kulhawy_k0_after_unloading']} | {r['valid']} |")
    if row not in section:
        bad.append(f"the table lacks {row}")


def fit_slope(points):
    xs = [math.log10(s) for s, _ in points]
    ys = [e for _, e in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return -sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def at(points, stress):
    for (s0, e0), (s1, e1) in zip(points, points[1:]):
        if (s0 - stress) * (s1 - stress) <= 0 and s0 != s1:
            return e0 + (e1 - e0) * (stress - s0) / (s1 - s0)
    raise ValueError(stress)


lines = (l for l in open(os.path.join(root, "assets/validation/karlsruhe_fine_sand_oedometer.csv"))
         if not l.startswith("#"))
tests = defaultdict(list)
for r in csv.DictReader(lines):
    tests[r["test_id"]].append((float(r["sigma1_kPa"]), float(r["e"])))
plastic, cc, cs = [], [], []
for pts in tests.values():
    k = max(range(len(pts)), key=lambda i: pts[i][0])
    j = k
    while j + 1 < len(pts) and pts[j + 1][0] <= pts[j][0]:
        j += 1
    load, unload = pts[:k + 1], pts[k:j + 1]
    e25, emax, e25u = at(load, 25), pts[k][1], at(unload, 25)
    plastic.append((e25 - e25u) / (e25 - emax))
    cc.append(fit_slope([p for p in load if 100 <= p[0] <= 410]))
    cs.append(fit_slope([p for p in unload if p[0] >= 25]))
for name, values, digits in (("plastic share", plastic, 2), ("Cc", cc, 3), ("Cs", cs, 3)):
    quoted = f"{min(values):.{digits}f}–{max(values):.{digits}f}"
    if quoted not in section:
        bad.append(f"the sand's {name} range should read {quoted}")

if bad:
    print("\n".join(bad))
    sys.exit(1)
print("docs/oedometer.md agrees with its CSV and with the Karlsruhe fine sand data")
