#!/usr/bin/env python3
"""The apparatus-choice tables of docs/shear-box.md from the campaigns' output.

Each choice is a campaign of its scene here (and the smooth box, the base
scene assets/scenes/shear_box_poured.toml) over the same five specimens:

    simsols campaign SCENE --sizes 6.35 --layers 4 --stresses 160 --seeds 5 --out RUNS/<choice>

with <choice> one of smooth, rough_inserts, wall_friction, wide_gap,
floating, tilting_cap. Then

    python3 assets/scenes/apparatus_choices/tables.py RUNS

writes docs/img/apparatus_choices.csv (each choice's ensemble, from its
ensemble.csv) and docs/img/apparatus_choices_tests.csv (every test, from its
summary.csv); tests/layout/check_shear_campaign_tables.py checks the docs'
tables against both, the paired changes recomputed from the tests.
"""
import csv
import os
import sys

# folder, the name the tables give it, the choice it differs from in one setting
CHOICES = [
    ("smooth", "smooth (the paper's box)", ""),
    ("rough_inserts", "rough inserts", "smooth (the paper's box)"),
    ("wall_friction", "side plates μ_w = 0.249", "smooth (the paper's box)"),
    ("wide_gap", "gap 0.8 d", "smooth (the paper's box)"),
    ("floating", "floating upper half, μ_w = 0.249", "side plates μ_w = 0.249"),
    ("tilting_cap", "cap free to tilt", "smooth (the paper's box)"),
]
ENSEMBLE = [("peak_deg", "peak_friction_angle_deg"), ("peak_ci95", "peak_ci95"),
            ("residual_deg", "residual_friction_angle_deg"), ("residual_ci95", "residual_ci95"),
            ("residual_plane_deg", "residual_friction_angle_plane_deg"),
            ("residual_plane_ci95", "residual_plane_ci95"),
            ("max_dilatancy_deg", "max_dilatancy_angle_deg"),
            ("max_dilatancy_ci95", "max_dilatancy_ci95"),
            ("wall_load_percent", "wall_load_percent"), ("wall_load_ci95", "wall_load_ci95"),
            ("critical_state_reached", "critical_state_reached"),
            ("tests_with_dynamic_events", "tests_with_dynamic_events")]
TESTS = ["seed", "peak_friction_angle_deg", "residual_friction_angle_deg",
         "residual_friction_angle_plane_deg", "max_dilatancy_angle_deg", "wall_load_percent",
         "critical_state", "dynamic_events", "valid", "upper_half_rise_mm", "cap_tilt_max_deg",
         "steps"]


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: tables.py RUNS (the folder holding one campaign per choice)")
    runs = sys.argv[1]
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..")
    out = os.path.join(root, "docs", "img")
    ensemble, tests = [], []
    for folder, name, base in CHOICES:
        e = rows(os.path.join(runs, folder, "ensemble.csv"))
        if len(e) != 1:
            sys.exit(f"{runs}/{folder}/ensemble.csv: expected one size and stress, found {len(e)} rows")
        ensemble.append([name, base, e[0]["specimens"]] + [e[0][k] for _, k in ENSEMBLE])
        for t in rows(os.path.join(runs, folder, "summary.csv")):
            tests.append([name] + [t[k] for k in TESTS])
    with open(os.path.join(out, "apparatus_choices.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["choice", "paired_with", "specimens"] + [k for k, _ in ENSEMBLE])
        w.writerows(ensemble)
    with open(os.path.join(out, "apparatus_choices_tests.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["choice"] + TESTS)
        w.writerows(tests)
    print(f"wrote {len(ensemble)} choices and {len(tests)} tests to docs/img/apparatus_choices*.csv")


if __name__ == "__main__":
    main()
