#!/usr/bin/env python3
"""One source for the direct shear campaign's headline tables: every row of
the shipped ensemble and envelope CSVs (docs/img/campaign_ensemble.csv,
docs/img/campaign_envelopes.csv, as `simsols campaign --seeds` writes them)
appears in docs/shear-box.md as the campaign's summary.md prints it, and the
apparatus-choice tables (docs/img/apparatus_choices.csv, the paired
changes recomputed from apparatus_choices_tests.csv) likewise, with the
wall friction they name the measured median of the shipped VSSUQ data.
  tests/layout/check_shear_campaign_tables.py [REPO_ROOT]"""
import csv
import math
import os
import sys

from ensemble_stats import mean_ci

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")


def rows_of(name):
    return list(csv.DictReader(open(os.path.join(root, "docs/img", name))))


def pm(value, spread, digits):
    v = float(value)
    text = f"{v:.{digits}f}"
    if spread not in ("", None) and math.isfinite(float(spread)):
        text += f" ± {float(spread):.{digits}f}"
    return text


def g(x):
    return f"{float(x):g}"


doc = open(os.path.join(root, "docs/shear-box.md"), encoding="utf-8").read()
bad = []

# the ensemble rows: | d | sigma | specimens | peak | residual | psi | critical | dynamic |
for r in rows_of("campaign_ensemble.csv"):
    row = (f"| {g(r['diameter_mm'])} | {g(r['normal_stress_kPa'])} | {r['specimens']} | "
           f"{pm(r['peak_friction_angle_deg'], r['peak_ci95'], 2)} | "
           f"{pm(r['residual_friction_angle_deg'], r['residual_ci95'], 2)} | "
           f"{pm(r['max_dilatancy_angle_deg'], r['max_dilatancy_ci95'], 1)} | "
           f"{r['critical_state_reached']} | {r['tests_with_dynamic_events']} |")
    if row not in doc:
        bad.append(f"docs/shear-box.md lacks the ensemble row {row}")

# the envelope rows: | d | strength | phi | c | specimens | ...
for r in rows_of("campaign_envelopes.csv"):
    if not r["phi_deg"]:
        continue
    head = (f"| {g(r['diameter_mm'])} | {r['strength']} | {pm(r['phi_deg'], r['phi_spread_deg'], 2)} | "
            f"{pm(r['c_kPa'], r['c_spread_kPa'], 2)} | {r['specimens']} |")
    if head not in doc:
        bad.append(f"docs/shear-box.md lacks the envelope row starting {head}")

# the apparatus choices: | choice | specimens | peak | residual | residual on the plane | psi | wall load |
for r in rows_of("apparatus_choices.csv"):
    row = (f"| {r['choice']} | {r['specimens']} | {pm(r['peak_deg'], r['peak_ci95'], 2)} | "
           f"{pm(r['residual_deg'], r['residual_ci95'], 2)} | "
           f"{pm(r['residual_plane_deg'], r['residual_plane_ci95'], 2)} | "
           f"{pm(r['max_dilatancy_deg'], r['max_dilatancy_ci95'], 1)} | "
           f"{pm(r['wall_load_percent'], r['wall_load_ci95'], 2)} |")
    if row not in doc:
        bad.append(f"docs/shear-box.md lacks the apparatus-choice row {row}")

# the side plates' friction named in the table is the measured median of
# glass on acrylic in the shipped VSSUQ data
lines = (l for l in open(os.path.join(root, "assets/materials/glass_beads_vssuq.csv")) if not l.startswith("#"))
mu = sorted(float(r["value"]) for r in csv.DictReader(lines) if r["quantity"] == "mupw_glass-acrylic")
median = (mu[len(mu) // 2] + mu[(len(mu) - 1) // 2]) / 2
if not any(f"μ_w = {median:.3f}" in r["choice"] for r in rows_of("apparatus_choices.csv")):
    bad.append(f"the wall-friction choice should name the measured median μ_w = {median:.3f}")

# the paired changes: the same seeds, each choice's value minus its
# baseline's, mean +- t(0.975, n-1) sd / sqrt(n)


def paired(choice, base, key):
    by = {}
    for r in rows_of("apparatus_choices_tests.csv"):
        by.setdefault(r["choice"], {})[r["seed"]] = float(r[key])
    d = [by[choice][k] - by[base][k] for k in sorted(by[base]) if k in by[choice]]
    return mean_ci(d)


# each choice against the box it differs from in that one setting (paired_with)
for r in rows_of("apparatus_choices.csv"):
    c, base = r["choice"], r["paired_with"]
    if not base:
        continue
    cells = []
    for key, digits in (("peak_friction_angle_deg", 2), ("residual_friction_angle_deg", 2),
                        ("max_dilatancy_angle_deg", 1)):
        m, hw = paired(c, base, key)
        cells.append(f"{m:+.{digits}f} ± {hw:.{digits}f}")
    row = f"| {c} | {base} | " + " | ".join(cells) + " |"
    if row not in doc:
        bad.append(f"docs/shear-box.md lacks the paired row {row}")

if bad:
    print("\n".join(bad))
    sys.exit(1)
print("shear campaign and apparatus-choice tables agree with their CSVs")
