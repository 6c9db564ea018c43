#!/usr/bin/env python3
"""One source for docs/calibration.md's figures of Karlsruhe fine sand: each
table row is made here from the shipped files and must stand in the doc.
  density map:  assets/calibration/kfs/density_map.py (packing.csv, the measured file)
  parameters:   docs/img/kfs_parameters.csv (the calibration's parameters.csv), and
                assets/calibration/kfs/calibrated.toml must hold its calibrated values
  curves:       docs/img/kfs_curves.csv (its curves.csv)
  predictions:  assets/calibration/kfs_predictions.csv (when present)
  oedometer:    assets/calibration/kfs/kfs_oedometer_predictions.csv (when present)
  recovery:     assets/calibration/recovery/recovery.csv (the two-parameter recovery study)
                and recovery_budget32.csv (some of it again with twice the budget, when present)
  tests/layout/check_calibration_tables.py [REPO_ROOT] [--print]
--print writes the tables instead of checking them."""
import csv
import importlib.util
import os
import re
import sys

root = sys.argv[1] if len(sys.argv) > 1 and not sys.argv[1].startswith("--") else \
    os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
kfs = os.path.join(root, "assets", "calibration", "kfs")
img = os.path.join(root, "docs", "img")
SYMBOL = {"mu_s": "μ_s", "mu_r": "μ_r (m)", "stress_ratio": "q/p′", "volumetric_strain": "ε_v (%)"}


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def g(x, digits=3):
    return f"{float(x):.{digits}g}"


def density_rows():
    spec = importlib.util.spec_from_file_location("density_map", os.path.join(kfs, "density_map.py"))
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    _, _, out = m.mapping()
    return [f"| {n} | {e_sand:.4f} | {100 * dr:.1f} % | {e:.4f} | {mu} |" for n, e_sand, dr, e, mu in out]


def parameter_rows():
    return [f"| {SYMBOL.get(r['parameter'], r['parameter'])} | {g(r['min'])}–{g(r['max'])} ({r['scale']}) | "
            f"{g(r['calibrated'])} | {g(r['mean'])} ± {g(r['sd'], 2)} | {g(r['lo95'])}–{g(r['hi95'])} |"
            for r in rows(os.path.join(img, "kfs_parameters.csv"))]


def curve_rows():
    return [f"| {r['target']} | {SYMBOL.get(r['quantity'], r['quantity'])} | {g(r['rms_misfit'])} | "
            f"{g(r['seed_scatter'])} | {g(r['misfit_D'])} |" for r in rows(os.path.join(img, "kfs_curves.csv"))]


def prediction_rows():
    path = os.path.join(root, "assets", "calibration", "kfs_predictions.csv")
    if not os.path.exists(path):
        return []
    return [f"| {r['sigma3_kPa']} | {r['Dr_pct']} % | {r['phi_peak_deg']} ({r['phi_peak_lo95_deg']}–"
            f"{r['phi_peak_hi95_deg']}) | {r['eps1_at_peak_pct']} ± {r['eps1_at_peak_ci95_pct']} | "
            f"{r['epsv_at_10pct_pct']} ± {r['epsv_at_10pct_ci95_pct']} | "
            f"{r['epsv_at_20pct_pct']} ± {r['epsv_at_20pct_ci95_pct']} |"
            for r in rows(path)]


def oedometer_rows():
    path = os.path.join(kfs, "kfs_oedometer_predictions.csv")
    if not os.path.exists(path):
        return []
    out = []
    for r in rows(path):
        at = [f"{r[f'eps_meas_{s}kPa']} / {r[f'eps_pred_{s}kPa']} ± {r[f'pi95_{s}kPa']}" for s in (100, 200, 380)]
        out.append(f"| {r['test']} | {r['Dr_pct']} % | " + " | ".join(at) +
                   f" | {r['rms_error_pct']} | {r['band_sd_pct']} | {r['inside_pct']} % |")
    with open(path) as f:
        summary = [line[2:].strip() for line in f if line.startswith("# At 380 kPa")]
    m = re.search(r"error ([0-9.]+) %.*", " ".join(summary)) if summary else None
    if m:
        out.append(f"the r.m.s. error of the twelve predictions at 380 kPa is {m.group(1)} %")
    with open(path) as f:
        text = f.read()
    m = re.search(r"about a straight line in D_r\) ([0-9.]+) %", text)
    if m:
        out.append(f"the tests' own scatter about a straight line in D_r is {m.group(1)} %")
    return out


def recovery_rows(name="recovery.csv"):
    path = os.path.join(root, "assets", "calibration", "recovery", name)
    if not os.path.exists(path):
        return []
    by = {}
    for r in rows(path):
        by.setdefault((r["truth"], r["specimen"], r["designs"]), {})[r["parameter"]] = r
    out = []
    for (truth, specimen, designs), p in by.items():
        # mu_s to three decimals; mu_r (m) over the diameter, 1 mm
        f = {"mu_s": lambda x: f"{float(x):.3f}", "mu_r": lambda x: f"{1e3 * float(x):.3f}"}
        cells = [f"{f[n](p[n]['true'])} | {f[n](p[n]['calibrated'])} ({f[n](p[n]['lo95'])}–"
                 f"{f[n](p[n]['hi95'])}){'' if p[n]['inside'] == '1' else ' outside'}"
                 for n in ("mu_s", "mu_r")]
        out.append(f"| {truth} | {specimen} | {designs} | " + " | ".join(cells) + " |")
    inside = sum(int(p[n]["inside"]) for p in by.values() for n in p)
    out.append(f"the truth lies inside the 95 % interval in {inside} of {2 * len(by)} cases")
    return out


def calibrated_agrees():
    text = open(os.path.join(kfs, "calibrated.toml")).read()
    bad = []
    for r in rows(os.path.join(img, "kfs_parameters.csv")):
        m = re.search(r"""['"]%s['"]\s*=\s*([0-9.eE+-]+)""" % re.escape(r["key"]), text)
        if not m or abs(float(m.group(1)) - float(r["calibrated"])) > 1e-5 * abs(float(r["calibrated"])):
            bad.append(f"calibrated.toml: {r['key']} is {m.group(1) if m else 'missing'}, "
                       f"kfs_parameters.csv says {r['calibrated']}")
    return bad


tables = {"density": density_rows(), "parameters": parameter_rows(), "curves": curve_rows(),
          "predictions": prediction_rows(), "oedometer": oedometer_rows(), "recovery": recovery_rows(),
          "recovery, larger budget": recovery_rows("recovery_budget32.csv")}
if "--print" in sys.argv:
    for name, lines in tables.items():
        print(f"# {name}\n" + "\n".join(lines) + "\n")
    sys.exit(0)
doc = open(os.path.join(root, "docs", "calibration.md")).read()
missing = [f"{name}: {line}" for name, lines in tables.items() for line in lines if line not in doc]
missing += calibrated_agrees()
if missing:
    print("docs/calibration.md or calibrated.toml differs from the shipped CSVs; rows expected:")
    print("\n".join(missing))
    sys.exit(1)
print(f"{sum(len(v) for v in tables.values())} rows of docs/calibration.md agree with their CSVs")
