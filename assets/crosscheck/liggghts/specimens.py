#!/usr/bin/env python3
"""The cross-check over several specimens: one row per (specimen, run), the
measures of compare.py (plain Python 3).

    specimens.py OUT.csv SEED:LABEL:DIR [SEED:LABEL:DIR ...]

DIR is a run.sh output folder (liggghts_shear.csv) or a SimSols shear-test
folder (shear.csv); SEED the specimen's seed ([shear_box.specimen] seed),
LABEL the code and law ("LIGGGHTS epsd2", "SimSols constant_torque", ...).
Writes OUT.csv (height_mm, first_peak, first_peak_at_mm, window_mean over
2.3..6 mm, dilation_end_mm, dilation_min_mm, collapse_fall_mm) and prints
the mean and sample standard deviation of each label's rows.
"""
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compare  # noqa: E402

COLUMNS = ["height_mm", "first_peak", "first_peak_at_mm", "window_mean", "dilation_end_mm",
           "dilation_min_mm", "collapse_fall_mm"]


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out = []
    for arg in sys.argv[2:]:
        seed, label, folder = arg.split(":", 2)
        m = compare.folder_measures(folder, 2.3, 6.0)
        out.append({"seed": int(seed), "run": label, **{k: m[k] for k in COLUMNS}})
    tmp = sys.argv[1] + ".tmp"
    with open(tmp, "w", newline="") as f:
        f.write("# LIGGGHTS cross-check, 2.38125 mm, 160 kPa, one row per specimen and run; "
                "heights, displacements and dilations in mm, first_peak and window_mean "
                "(2.3-6 mm) are tau/sigma; written by assets/crosscheck/liggghts/specimens.py\n")
        w = csv.DictWriter(f, fieldnames=["seed", "run"] + COLUMNS)
        w.writeheader()
        for r in out:
            w.writerow({k: (f"{v:.5g}" if isinstance(v, float) else v) for k, v in r.items()})
    os.replace(tmp, sys.argv[1])
    for label in dict.fromkeys(r["run"] for r in out):
        rows = [r for r in out if r["run"] == label]
        parts = []
        for k in ("first_peak", "window_mean", "dilation_end_mm"):
            mean, sd = compare.mean_sd([r[k] for r in rows])
            parts.append(f"{k} {mean:.4g} +- {sd:.2g}")
        print(f"{label} ({len(rows)} specimens): " + ", ".join(parts))


if __name__ == "__main__":
    main()
