#!/usr/bin/env python3
"""One source for docs/periodic-cell.md's tables: each table under a
`<!-- periodic_NAME: ... -->` marker is the campaign's summary.md of
docs/img/periodic_NAME_summary.csv (the same rows, formatted as
app/experiment/periodic_cell/cell_campaign.cpp formats them), and the fit
of mu = mu0 + d I^(1/2) quoted for the frictionless spheres is the least
squares fit of that CSV's points.
  tests/layout/check_periodic_cell_tables.py [REPO_ROOT]"""
import csv
import math
import os
import sys

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
doc = open(os.path.join(root, "docs/periodic-cell.md"), encoding="utf-8").read()
bad = []


def rows_of(name):
    with open(os.path.join(root, f"docs/img/periodic_{name}_summary.csv")) as f:
        return list(csv.DictReader(f))


def markdown(rows):
    out = ["| p (kPa) | I | specimens | τ/σ_zz | φ_mob (°) | Φ | Z | ε_v |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        v = {k: float(x) for k, x in r.items()}
        out.append(f"| {v['p_kPa']:g} | {v['inertial_number']:g} | {int(v['specimens'])} | "
                   f"{v['stress_ratio']:.4f} ± {v['stress_ratio_ci95']:.4f} | "
                   f"{v['friction_angle_deg']:.2f} ± {v['friction_angle_ci95']:.2f} | "
                   f"{v['solid_fraction']:.4f} ± {v['solid_fraction_ci95']:.4f} | "
                   f"{v['coordination']:.3f} ± {v['coordination_ci95']:.3f} | "
                   f"{v['volumetric_strain']:.4f} ± {v['volumetric_strain_ci95']:.4f} |")
    return out


for name in ("frictionless", "glass", "paper_glass"):
    marker = f"<!-- periodic_{name}:"
    if marker not in doc:
        bad.append(f"no table marked {marker} in docs/periodic-cell.md")
        continue
    lines = doc[doc.index(marker):].splitlines()[1:]
    want = markdown(rows_of(name))
    got = lines[:len(want)]
    for w, g in zip(want, got):
        if w != g:
            bad.append(f"periodic_{name}: the docs say\n  {g}\nthe CSV gives\n  {w}")

rows = rows_of("frictionless")
x = [math.sqrt(float(r["inertial_number"])) for r in rows]
y = [float(r["stress_ratio"]) for r in rows]
mx, my = sum(x) / len(x), sum(y) / len(y)
d = sum((a - mx) * (b - my) for a, b in zip(x, y)) / sum((a - mx) ** 2 for a in x)
mu0 = my - d * mx
quote = f"μ₀ = {mu0:.3f}, d = {d:.2f} (d/μ₀ = {d / mu0:.1f})"
if quote not in doc:
    bad.append(f"the frictionless fit: the docs should say '{quote}'")

for b in bad:
    print(b)
sys.exit(1 if bad else 0)
