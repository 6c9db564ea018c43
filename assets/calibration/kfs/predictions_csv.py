#!/usr/bin/env python3
"""kfs_predictions.csv from a run of kfs_predict_triaxial.toml: one row per test.

  predictions_csv.py OUT > ../kfs_predictions.csv

Reads OUT/prediction.csv (`simsols predict`: each quantity's mean over the
specimens with Student's 95 % half-interval). The peak friction angle is
phi' = asin(3 eta / (6 + eta)) of the specimens' mean peak stress ratio
eta = q/p' (triaxial compression); its interval is the stress ratio's
interval mapped through the same function.
"""
import csv, math, os, re, sys


def phi(eta):
    return math.degrees(math.asin(3 * eta / (6 + eta)))


def main():
    out = sys.argv[1]
    rows = list(csv.DictReader(open(os.path.join(out, 'prediction.csv'))))
    by = {(r['test'], r['quantity']): r for r in rows}
    print('# Karlsruhe fine sand: blind predictions of drained triaxial compression (constant sigma3), made by SimSols')
    print('# with the material calibrated on the five tests at sigma3 = 100 kPa (assets/calibration/kfs/calibrated.toml,')
    print('# docs/calibration.md) before any measurement of these tests was read. Calibration data: Wichtmann &')
    print('# Triantafyllidis (2016), Acta Geotechnica 11:739-761. Each row: the mean of 5 specimens (a periodic cell of')
    print('# 300 scaled-up spheres) with its 95 % interval (Student). Dr_pct is the relative density of the 100 kPa test')
    print('# named in as_test. phi_peak from the mean peak q/p; eps1 and epsv in % (epsv compression positive).')
    print('sigma3_kPa,Dr_pct,as_test,specimens,phi_peak_deg,phi_peak_lo95_deg,phi_peak_hi95_deg,'
          'eps1_at_peak_pct,eps1_at_peak_ci95_pct,epsv_at_10pct_pct,epsv_at_10pct_ci95_pct,'
          'epsv_at_20pct_pct,epsv_at_20pct_ci95_pct')
    names = {21: 'TMD2', 51: 'TMD7', 63: 'TMD12', 79: 'TMD17', 85: 'TMD22'}
    for (test, quantity), r in by.items():
        if quantity != 'stress_ratio':
            continue
        m = re.match(r'Dr(\d+)_s3_(\d+)kPa', test)
        dr, s3 = int(m.group(1)), int(m.group(2))
        v = by[(test, 'volumetric_strain')]
        eta, ci = float(r['peak_mean']), float(r['peak_ci95'])
        print(f"{s3},{dr},{names[dr]},{r['specimens']},{phi(eta):.2f},{phi(eta - ci):.2f},{phi(eta + ci):.2f},"
              f"{float(r['x_at_peak_mean']):.2f},{float(r['x_at_peak_ci95']):.2f},"
              f"{float(v['at_10_mean']):.3f},{float(v['at_10_ci95']):.3f},"
              f"{float(v['at_20_mean']):.3f},{float(v['at_20_ci95']):.3f}")


if __name__ == '__main__':
    main()
