#!/usr/bin/env python3
"""One source for docs/triaxial.md's "A campaign over σ₃": its table is
recomputed here from the shipped campaign, docs/img/triaxial_campaign_tests.csv
(the campaign's summary.csv: one row per test, with its seed), each row the
mean over the specimens with its 95 % Student interval; the envelopes it
quotes are docs/img/triaxial_campaign_envelopes.csv (the campaign's
envelopes.csv), whose means and intervals are refitted here from the tests
(each specimen's envelope tangent to its own Mohr circles).
  tests/layout/check_triaxial_campaign_tables.py [REPO_ROOT] [--print]"""
import csv
import math
import os
import sys

from ensemble_stats import mean_ci

args = [a for a in sys.argv[1:] if a != "--print"]
root = args[0] if args else os.path.join(os.path.dirname(__file__), "..", "..")
# column of the tests' CSV, digits, the table's heading
COLUMNS = [("e0", 3, "e₀"), ("peak_phi_deg", 2, "peak φ′ (°)"), ("critical_phi_deg", 2, "critical φ′ (°)"),
           ("critical_void_ratio", 3, "e_cs"), ("critical_p_kPa", 1, "p′_cs (kPa)"),
           ("max_dilatancy_deg", 2, "ψ max (°)")]


def rows(name):
    return list(csv.DictReader(l for l in open(os.path.join(root, "docs/img", name)) if not l.startswith("#")))


def fit_circles(s1, s3):
    """Least squares t = c cos(phi) + s sin(phi) through the circles' tops (kPa)."""
    s = [(a + b) / 2 for a, b in zip(s1, s3)]
    t = [(a - b) / 2 for a, b in zip(s1, s3)]
    ms, mt = sum(s) / len(s), sum(t) / len(t)
    slope = sum((x - ms) * (y - mt) for x, y in zip(s, t)) / sum((x - ms) ** 2 for x in s)
    phi = math.asin(slope)
    return math.degrees(phi), (mt - slope * ms) / math.cos(phi)


tests = rows("triaxial_campaign_tests.csv")
stresses = sorted({float(r["sigma3_kPa"]) for r in tests})
table = ["| σ₃ (kPa) | specimens | " + " | ".join(h for _, _, h in COLUMNS) + " |",
         "|" + "---|" * (len(COLUMNS) + 2)]
for s3 in stresses:
    at = [r for r in tests if float(r["sigma3_kPa"]) == s3]
    cells = []
    for c, digits, _ in COLUMNS:
        m, ci = mean_ci([float(r[c]) for r in at])
        cells.append(f"{m:.{digits}f} ± {ci:.{digits}f}")
    table.append(f"| {s3:g} | {len(at)} | " + " | ".join(cells) + " |")
envelopes = {r["strength"]: r for r in rows("triaxial_campaign_envelopes.csv")}
bad = []
for strength, key in (("peak", "peak"), ("critical", "critical")):
    fits = []
    for seed in sorted({r["seed"] for r in tests}, key=int):
        at = [r for r in tests if r["seed"] == seed]
        fits.append(fit_circles([float(r[key + "_sigma1_kPa"]) for r in at],
                                [float(r[key + "_sigma3_kPa"]) for r in at]))
    (phi, phi_ci), (c, c_ci) = mean_ci([f[0] for f in fits]), mean_ci([f[1] for f in fits])
    e = envelopes[strength]
    for name, mine, shipped in (("phi", phi, e["phi_deg"]), ("phi interval", phi_ci, e["phi_spread_deg"]),
                                ("c", c, e["c_kPa"]), ("c interval", c_ci, e["c_spread_kPa"])):
        if abs(mine - float(shipped)) > 0.02:
            bad.append(f"{strength} {name}: the tests give {mine:.3f}, envelopes.csv {shipped}")
    table.append("")
    table.append(f"- {strength} envelope: φ′ = {float(e['phi_deg']):.2f} ± {float(e['phi_spread_deg']):.2f}°, "
                 f"c = {float(e['c_kPa']):.2f} ± {float(e['c_spread_kPa']):.2f} kPa "
                 f"({e['specimens']} specimens)")
if "--print" in sys.argv:
    print("\n".join(table))
    sys.exit(0)
doc = open(os.path.join(root, "docs/triaxial.md"), encoding="utf-8").read()
section = doc[doc.index("## A campaign over σ₃"):]
section = section[:section.index("\n## ", 3)]
for line in table:
    if line and line not in section:
        bad.append(f"docs/triaxial.md lacks: {line}")
if bad:
    print("\n".join(bad))
    sys.exit(1)
print(f"triaxial campaign table: {len(tests)} tests, {len(stresses)} stresses, rows and envelopes agree")
