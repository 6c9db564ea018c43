#!/usr/bin/env python3
"""One source for the measured-glass table of docs/shear-box.md: each
2.38 mm row's values for the scene as shipped (each cell's last: first peak
and where, largest when it differs, residual, largest dilatancy angle) are
those of the shipped campaign summary
docs/img/measured_glass_d2.38mm_summary.csv, and the
envelopes quoted are the least-squares fits of its residual rows, of the
second specimen's (..._seed2_summary.csv) and of both.
  tests/layout/check_measured_glass_table.py [REPO_ROOT]"""
import csv
import math
import os
import sys

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
rows = list(csv.DictReader(open(os.path.join(root, "docs/img/measured_glass_d2.38mm_summary.csv"))))
doc = open(os.path.join(root, "docs/shear-box.md"), encoding="utf-8").read()
section = doc[doc.index("## Measured glass"):]
bad = []
for r in rows:
    sigma = int(float(r["normal_stress_kPa"]))
    line = next((l for l in section.splitlines() if l.startswith(f"| 2.38 mm, {sigma} kPa |")), None)
    if line is None:
        bad.append(f"no row for {sigma} kPa")
        continue
    cells = [c.strip() for c in line.strip("|").split("|")]
    peak = f"{float(r['peak_friction_angle_deg']):.2f} at {float(r['peak_displacement_mm']):.2f} mm"
    if not cells[1].split(" / ")[-1].startswith(peak):
        bad.append(f"{sigma} kPa: peak cell '{cells[1]}' does not hold '{peak}'")
    if float(r["max_friction_angle_deg"]) > float(r["peak_friction_angle_deg"]) + 1e-9:
        largest = f"(largest {float(r['max_friction_angle_deg']):.2f})"
        if largest not in cells[1]:
            bad.append(f"{sigma} kPa: peak cell '{cells[1]}' does not hold '{largest}'")
    for col, key in ((2, "residual_friction_angle_deg"), (3, "max_dilatancy_angle_deg")):
        want = f"{float(r[key]):.2f}"
        if cells[col].split(" / ")[-1] != want:
            bad.append(f"{sigma} kPa: cell '{cells[col]}' should end '/ {want}' ({key})")
# the residual envelopes, tau_res = c + sigma tan(phi) by least squares: the
# shipped scene's, the second specimen's and both together
def residual_phi(rs):
    xs = [float(r["normal_stress_kPa"]) for r in rs]
    ys = [float(r["residual_tau_kPa"]) for r in rs]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return math.degrees(math.atan(slope))


seed2 = list(csv.DictReader(open(os.path.join(root, "docs/img/measured_glass_d2.38mm_seed2_summary.csv"))))
phis = [residual_phi(rows), residual_phi(seed2), residual_phi(rows + seed2)]
for what, phi in zip(("the shipped scene's", "the second specimen's", "both specimens'"), phis):
    if f"φ = {phi:.2f}" not in section:
        bad.append(f"{what} residual envelope should read 'φ = {phi:.2f}'")
for b in bad:
    print("check_measured_glass_table:", b)
if not bad:
    print(f"check_measured_glass_table: {len(rows)} rows and the residual envelopes "
          f"({', '.join(f'{p:.2f}' for p in phis)} deg) agree")
sys.exit(1 if bad else 0)
