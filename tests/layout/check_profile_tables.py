#!/usr/bin/env python3
"""One source for the fast profile's figures: assets/accuracy/profiles.csv
(what the lab shows) holds the paired differences fast - paper recomputed
here from the shipped per-test CSVs, the same specimens (seeds) under both
profiles:
  layered: docs/img/campaign_tests.csv (paper) and fast_campaign_tests.csv
  poured:  docs/img/apparatus_choices_tests.csv's smooth box (paper) and
           fast_poured_tests.csv
and docs/accuracy.md quotes each of its rows, the layered campaign's rows
size by size, and the levers measured one by one against the paper
profile (docs/img/lever_*_tests.csv, campaign summaries of the same
specimens: | lever | tests | steps ratio | Δ peak | Δ residual | Δ ψ |).
  tests/layout/check_profile_tables.py [REPO_ROOT] [--write]
--write rewrites profiles.csv from the per-test CSVs instead."""
import csv
import os
import sys

from ensemble_stats import mean_ci

root = sys.argv[1] if len(sys.argv) > 1 and not sys.argv[1].startswith("--") else \
    os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
img = os.path.join(root, "docs", "img")


def rows(name):
    with open(os.path.join(img, name)) as f:
        return list(csv.DictReader(f))


def paired(pairs):
    out = {"tests": len(pairs)}
    for name, col in (("peak_diff", "peak_friction_angle_deg"), ("residual_diff", "residual_friction_angle_deg"),
                      ("dilatancy_diff", "max_dilatancy_angle_deg")):
        d = [float(f[col]) - float(p[col]) for p, f in pairs]
        out[name] = mean_ci(d)
    out["step_ratio"] = sum(float(p["steps"]) for p, _ in pairs) / sum(float(f["steps"]) for _, f in pairs)
    return out


def valid(r):
    return r.get("valid", "yes") == "yes"


key = lambda r: (r["diameter_mm"], r["normal_stress_kPa"], r["seed"])
paper = {key(r): r for r in rows("campaign_tests.csv")}
layered = [(paper[key(f)], f) for f in rows("fast_campaign_tests.csv")
           if key(f) in paper and valid(paper[key(f)]) and valid(f)]
smooth = {r["seed"]: r for r in rows("apparatus_choices_tests.csv") if r["choice"] == "smooth (the paper's box)"}
poured = [(smooth[f["seed"]], f) for f in rows("fast_poured_tests.csv") if f["seed"] in smooth and valid(f)]

header = ("profile,specimen,tests,step_ratio,peak_diff_deg,peak_diff_ci95,residual_diff_deg,"
          "residual_diff_ci95,dilatancy_diff_deg,dilatancy_diff_ci95")
lines = []
for spec, pairs in (("layered", layered), ("poured", poured)):
    o = paired(pairs)
    cells = [f"{o[k][0]:+.2f},{o[k][1]:.2f}" for k in ("peak_diff", "residual_diff", "dilatancy_diff")]
    lines.append(f"fast,{spec},{o['tests']},{o['step_ratio']:.1f}," + ",".join(cells))
notes = ("# The fast profile against the paper profile on the same specimens (seeds): mean of the\n"
         "# paired differences fast - paper (deg) and the half width of its 95 % Student interval;\n"
         "# step_ratio: the paper profile's time steps over the fast one's, all stages.\n"
         "# Written by tests/layout/check_profile_tables.py --write from docs/img/campaign_tests.csv,\n"
         "# fast_campaign_tests.csv, apparatus_choices_tests.csv and fast_poured_tests.csv.\n")
path = os.path.join(root, "assets", "accuracy", "profiles.csv")
text = notes + header + "\n" + "\n".join(lines) + "\n"
if "--write" in sys.argv:
    with open(path, "w") as f:
        f.write(text)
    print(text)
    sys.exit(0)
bad = []
if open(path).read() != text:
    bad.append(f"{path} differs from the paired differences of the shipped tests:\n{text}")
doc = open(os.path.join(root, "docs", "accuracy.md")).read()
for line in lines:
    c = line.split(",")
    row = (f"| {c[1]} | {c[2]} | {c[3]}× | {c[4]} ± {c[5]} | {c[6]} ± {c[7]} | {c[8]} ± {c[9]} |")
    if row not in doc:
        bad.append(f"docs/accuracy.md lacks the fast-profile row {row}")
# the layered campaign size by size: | d (mm) | tests | Δ φ peak | Δ φ residual | Δ ψ max |
for d in sorted({f["diameter_mm"] for _, f in layered}, key=float):
    o = paired([(p, f) for p, f in layered if f["diameter_mm"] == d])
    row = f"| {d} | {o['tests']} | " + " | ".join(
        f"{o[k][0]:+.2f} ± {o[k][1]:.2f}" for k in ("peak_diff", "residual_diff", "dilatancy_diff")) + " |"
    if row not in doc:
        bad.append(f"docs/accuracy.md lacks the fast-profile size row {row}")
LEVERS = (("E × 0.1, dt 0.5, I 2·10⁻³", "lever_soft_dt_i_tests.csv"),
          ("dt 0.5, I 2·10⁻³", "lever_dt_i_tests.csv"),
          ("E × 0.1", "lever_soft_tests.csv"))
for name, f in LEVERS:
    pairs = [(paper[key(r)], r) for r in rows(f) if key(r) in paper and valid(paper[key(r)]) and valid(r)]
    o = paired(pairs)
    sizes = ", ".join(sorted({r["diameter_mm"] for _, r in pairs}, key=float))
    row = (f"| {name} | {sizes} | {o['tests']} | {o['step_ratio']:.1f}× | " + " | ".join(
        f"{o[k][0]:+.2f} ± {o[k][1]:.2f}" for k in ("peak_diff", "residual_diff", "dilatancy_diff")) + " |")
    if row not in doc:
        bad.append(f"docs/accuracy.md lacks the lever row {row}")
if bad:
    print("\n".join(bad))
    sys.exit(1)
print("the fast profile's figures agree with the shipped tests")
