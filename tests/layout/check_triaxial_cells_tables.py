#!/usr/bin/env python3
"""One source for docs/triaxial.md's "Rigid against membrane": each row of
its table is docs/img/triaxial_cells.csv, whose means and 95 % intervals
(each cell's, and the paired membrane - rigid change) are recomputed here
from the tests in docs/img/triaxial_cells_tests.csv; and the rows of its
"A dense, rougher specimen" are docs/img/triaxial_dense_x2.csv's.
  tests/layout/check_triaxial_cells_tables.py [REPO_ROOT]"""
import csv
import os
import sys

from ensemble_stats import mean_ci

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
doc = open(os.path.join(root, "docs/triaxial.md"), encoding="utf-8").read()
section = doc[doc.index("### Rigid against membrane"):]
section = section[:section.index("\n## ")]
COLUMNS = ["initial_void_ratio", "peak_deg", "peak_axial_strain", "critical_deg", "critical_void_ratio",
           "max_dilatancy_deg", "final_volumetric_strain", "median_wall_internal_gap_percent",
           "end_membrane_axial_kPa", "end_membrane_shell_kPa"]
bad = []


def rows(name):
    return list(csv.DictReader(l for l in open(os.path.join(root, "docs/img", name)) if not l.startswith("#")))


tests = rows("triaxial_cells_tests.csv")
by = {}
for r in tests:
    by.setdefault(r["cell"], {})[r["seed"]] = r
seeds = sorted(set.intersection(*(set(v) for v in by.values())), key=int)
for r in rows("triaxial_cells.csv"):
    cells = [r["cell"], r["specimens"]] + [f"{r[c]} ± {r[c + '_ci95']}" for c in COLUMNS]
    line = "| " + " | ".join(cells) + " |"
    if line not in section:
        bad.append(f"the table lacks {line}")
    for c in COLUMNS:
        if " - " in r["cell"]:
            a, b = r["cell"].split(" - ")
            v = [float(by[a][s][c]) - float(by[b][s][c]) for s in seeds]
        else:
            v = [float(by[r["cell"]][s][c]) for s in seeds]
        m, ci = mean_ci(v)
        digits = len(r[c].split(".")[1]) if "." in r[c] else 0
        tol = 0.6 * 10 ** -digits + 1e-9
        if abs(m - float(r[c])) > tol or abs(ci - float(r[c + "_ci95"])) > tol:
            bad.append(f"{r['cell']} {c}: the tests give {m:.4f} ± {ci:.4f}, the table {r[c]} ± {r[c + '_ci95']}")
    if int(r["specimens"]) != len(seeds):
        bad.append(f"{r['cell']}: {r['specimens']} specimens, the tests have {len(seeds)}")
# the dense specimen's table ("A dense, rougher specimen"): its rows are
# docs/img/triaxial_dense_x2.csv's (one run per cell, no interval)
dense_doc = doc[doc.index("### A dense, rougher specimen"):]
dense_doc = dense_doc[:dense_doc.index("\n## ")]
DENSE = ["cell", "initial_void_ratio", "peak_deg", "peak_axial_strain", "critical_deg", "max_dilatancy_deg",
         "final_volumetric_strain", "median_wall_internal_gap_percent", "end_membrane_axial_kPa"]
dense_rows = rows("triaxial_dense_x2.csv")
for r in dense_rows:
    line = "| " + " | ".join(r[c] for c in DENSE) + " |"
    if line not in dense_doc:
        bad.append(f"the dense specimen's table lacks {line}")
if bad:
    print("\n".join(bad))
    sys.exit(1)
print(f"triaxial cells table: {len(seeds)} specimens in both cells, rows and intervals agree; "
      f"the dense specimen's {len(dense_rows)} rows agree")
