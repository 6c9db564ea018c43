#!/usr/bin/env python3
"""The numbers of the LIGGGHTS cross-check, for both codes (plain Python 3).

    compare.py LIGGGHTS_OUTDIR SIMSOLS_TEST_DIR [FROM_MM TO_MM]

LIGGGHTS_OUTDIR is a run.sh output folder (liggghts_shear.csv, summary.txt);
SIMSOLS_TEST_DIR a SimSols shear-test folder (shear.csv, summary.txt), e.g.
the d2.38125mm_160kPa folder of `simsols campaign --sizes 2.38125
--stresses 160`. Both are read by their column names (displacement_mm,
tau_kPa, sigma_kPa, tau_over_sigma, dilation_mm), so the same definitions
apply to both:

  height       specimen height (platen above the floor) when shearing begins
  collapse     the largest fall of the platen over 0.1 mm of shear (5 rows
               of 0.02 mm), where it starts, and the change of tau over it
  tau drop     the largest fall of tau from one row to the next
  first peak   SimSols' first peak (solver/apparatus/shear_box/shear_analysis.cpp, first_peak)
  largest      the largest tau/sigma and where
  window mean  mean tau/sigma over FROM_MM..TO_MM (default 1..6 mm) and over
               the last 20 % (SimSols' residual window), with the standard
               deviation of the rows
  dilation     dilation at the end, lowest dilation and where
"""
import math
import os
import sys


def read_csv(path):
    with open(path) as f:
        head = f.readline().strip().split(",")
        rows = []
        for line in f:
            if line.strip():
                rows.append(dict(zip(head, (float(x) for x in line.strip().split(",")))))
    return rows


def read_summary(path):
    kv = {}
    if os.path.exists(path):
        for line in open(path):
            if " = " in line:
                k, v = line.split(" = ", 1)
                kv[k.strip()] = v.strip()
    return kv


def first_peak(rows, target, recovery_mm, softening=0.05):
    ok = [r for r in rows if r["sigma_kPa"] > 0.5 * target]
    top = max((r["tau_kPa"] / r["sigma_kPa"] for r in ok), default=0)
    end = rows[-1]["displacement_mm"]
    res = [r["tau_kPa"] / r["sigma_kPa"] for r in ok if r["displacement_mm"] >= 0.8 * end * (1 - 1e-7)]
    floor = max(0.25 * top, sum(res) / len(res) if res else 0)
    best, at, fell_at = 0.0, 0.0, None
    for r in ok:
        ratio, x = r["tau_kPa"] / r["sigma_kPa"], r["displacement_mm"]
        if ratio > best:
            best, at, fell_at = ratio, x, None
        elif fell_at is None and best >= floor and ratio < (1 - softening) * best:
            fell_at = x
        if fell_at is not None and x - fell_at >= recovery_mm:
            break  # softened and not regained within a quarter of a bead diameter
    return best, at


def mean_sd(values):
    if not values:
        return float("nan"), float("nan")
    m = sum(values) / len(values)
    return m, math.sqrt(sum((v - m) ** 2 for v in values) / max(1, len(values) - 1))


def measures(rows, height, target, diameter_mm, lo, hi):
    out = {"height_mm": height}
    best = (0.0, 0, 0.0)
    for i in range(len(rows) - 5):
        fall = rows[i]["dilation_mm"] - rows[i + 5]["dilation_mm"]
        if fall > best[0]:
            best = (fall, i, rows[i + 5]["tau_kPa"] - rows[i]["tau_kPa"])
    out["collapse_fall_mm"] = best[0]
    out["collapse_at_mm"] = rows[best[1]]["displacement_mm"]
    out["collapse_dtau_kPa"] = best[2]
    drop = max(range(1, len(rows)), key=lambda i: rows[i - 1]["tau_kPa"] - rows[i]["tau_kPa"])
    out["tau_drop_kPa"] = rows[drop - 1]["tau_kPa"] - rows[drop]["tau_kPa"]
    out["tau_drop_at_mm"] = rows[drop]["displacement_mm"]
    out["first_peak"], out["first_peak_at_mm"] = first_peak(rows, target, 0.25 * diameter_mm)
    big = max(rows, key=lambda r: r["tau_over_sigma"])
    out["largest"], out["largest_at_mm"] = big["tau_over_sigma"], big["displacement_mm"]
    w = [r["tau_over_sigma"] for r in rows if lo - 1e-9 <= r["displacement_mm"] <= hi + 1e-9]
    out["window_mean"], out["window_sd"] = mean_sd(w)
    out["window_rows"] = len(w)
    end = rows[-1]["displacement_mm"]
    last = [r["tau_over_sigma"] for r in rows if r["displacement_mm"] >= 0.8 * end * (1 - 1e-7)]
    out["last20_mean"], out["last20_sd"] = mean_sd(last)
    out["dilation_end_mm"] = rows[-1]["dilation_mm"]
    low = min(rows, key=lambda r: r["dilation_mm"])
    out["dilation_min_mm"], out["dilation_min_at_mm"] = low["dilation_mm"], low["displacement_mm"]
    out["sigma_min_kPa"] = min(r["sigma_kPa"] for r in rows)
    out["sigma_max_kPa"] = max(r["sigma_kPa"] for r in rows)
    out["sheared_mm"] = end
    return out


def folder_measures(folder, lo, hi, target=None, diameter_mm=None):
    """The measures of a run.sh folder (liggghts_shear.csv) or of a SimSols
    test folder (shear.csv); the normal stress and bead diameter from its
    summary.txt unless given."""
    s = read_summary(os.path.join(folder, "summary.txt"))
    lig = os.path.exists(os.path.join(folder, "liggghts_shear.csv"))
    rows = read_csv(os.path.join(folder, "liggghts_shear.csv" if lig else "shear.csv"))
    target = target if target is not None else float(s.get("normal_stress_kPa", 160))
    d = diameter_mm if diameter_mm is not None else float(s.get("bead_diameter_mm", 2.38125))
    return measures(rows, float(s["specimen_height_mm"]), target, d, lo, hi)


def main():
    if len(sys.argv) not in (3, 5):
        sys.exit(__doc__)
    lg, ss = sys.argv[1], sys.argv[2]
    lo, hi = (float(sys.argv[3]), float(sys.argv[4])) if len(sys.argv) == 5 else (1.0, 6.0)
    lsum, ssum = read_summary(os.path.join(lg, "summary.txt")), read_summary(os.path.join(ss, "summary.txt"))
    target = float(ssum.get("normal_stress_kPa", lsum.get("normal_stress_kPa", 160)))
    d = float(ssum.get("bead_diameter_mm", lsum.get("bead_diameter_mm", 2.38125)))
    a = folder_measures(lg, lo, hi, target, d)
    b = folder_measures(ss, lo, hi, target, d)
    print("%-22s %14s %14s" % ("", "LIGGGHTS", "SimSols"))
    for k in a:
        print("%-22s %14.5g %14.5g" % (k, a[k], b[k]))


if __name__ == "__main__":
    main()
