#!/usr/bin/env python3
"""One source for the measured-glass table of docs/shear-box.md: each
2.38 mm row's values for the scene as shipped (each cell's last: first peak
and where, largest when it differs, residual, largest dilatancy angle) are
those of the shipped
campaign summary docs/img/measured_glass_d2.38mm_summary.csv, and the
envelope quoted is the least-squares fit of its residual rows.
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
# the residual envelope: tau_res = c + sigma tan(phi), least squares
xs = [float(r["normal_stress_kPa"]) for r in rows]
ys = [float(r["residual_tau_kPa"]) for r in rows]
n = len(xs)
mx, my = sum(xs) / n, sum(ys) / n
slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
phi = math.degrees(math.atan(slope))
if f"residual φ = {phi:.2f}" not in section:
    bad.append(f"the residual envelope should read 'residual φ = {phi:.2f}'")
for b in bad:
    print("check_measured_glass_table:", b)
if not bad:
    print(f"check_measured_glass_table: {n} rows and the residual envelope ({phi:.2f} deg) agree")
sys.exit(1 if bad else 0)
