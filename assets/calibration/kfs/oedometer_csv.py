#!/usr/bin/env python3
"""kfs_oedometer_predictions.csv from a run of kfs_predict_oedometer.toml: one row per oedometer test.

  oedometer_csv.py OUT > kfs_oedometer_predictions.csv

Reads OUT/prediction.csv and OUT/band_OE<k>_axial_strain.csv (`simsols
predict`: the specimens' mean curve with the half-width of the 95 %
prediction interval of one more specimen) and the measured curves
(assets/validation/karlsruhe_fine_sand_oedometer.csv, loading branch). Both
strains are counted from sigma1 = 25 kPa (the prediction's zero_at). At
100, 200 and 380 kPa: measured, predicted mean and the interval's
half-width, by linear interpolation (380 kPa: the highest stress every
specimen's rows reach). The experiments' own scatter is taken as the
residual standard deviation of the measured strain at 380 kPa
about a straight line in D_r (the database has no repeated test): a
prediction error below it cannot be told from the tests' scatter.
"""
import csv, importlib.util, math, os, sys

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, '..', '..', 'validation', 'karlsruhe_fine_sand_oedometer.csv')
AT = (100, 200, 380)  # kPa: every specimen's rows reach 388 kPa (the turn at 407 kPa falls between rows)
ZERO = 25             # kPa, as the prediction's zero_at


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith('#')))


def num(text):
    return float(text) if text else math.nan  # an empty cell: a point the band does not reach


def interp(xs, ys, x):
    for i in range(len(xs) - 1):
        if xs[i] <= x <= xs[i + 1] and xs[i + 1] > xs[i]:
            return ys[i] + (ys[i + 1] - ys[i]) * (x - xs[i]) / (xs[i + 1] - xs[i])
    return math.nan


def measured(test):
    rs = [r for r in rows(DATA) if r['test_id'] == test]
    xs, ys = [], []
    for r in rs:  # the loading branch: up to the largest stress
        xs.append(float(r['sigma1_kPa']))
        ys.append(float(r['eps1_pct']))
        if xs[-1] >= 407:
            break
    zero = interp(xs, ys, ZERO)
    return xs, [y - zero for y in ys]


def densities():
    spec = importlib.util.spec_from_file_location('density_map', os.path.join(HERE, 'density_map.py'))
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    _, _, out = m.mapping(m.oedometer_tests)
    return {n: (e_sand, 100 * dr) for n, e_sand, dr, e, mu in out}


def line_residual_sd(x, y):
    n = len(x)
    mx, my = sum(x) / n, sum(y) / n
    b = sum((a - mx) * (c - my) for a, c in zip(x, y)) / sum((a - mx) ** 2 for a in x)
    res = [c - my - b * (a - mx) for a, c in zip(x, y)]
    return math.sqrt(sum(r * r for r in res) / (n - 2))


def main():
    out = sys.argv[1]
    pred = {r['test']: r for r in rows(os.path.join(out, 'prediction.csv')) if r['quantity'] == 'axial_strain'}
    dens = densities()
    table = []
    for test in sorted(pred, key=lambda t: int(t[2:])):
        band = rows(os.path.join(out, f'band_{test}_axial_strain.csv'))
        bx = [float(r['x']) for r in band]
        mx, my = measured(test)
        row = [test, f'{dens[test][1]:.1f}', f'{dens[test][0]:.4f}']
        for s in AT:
            mean = interp(bx, [num(r['mean']) for r in band], s)
            half = interp(bx, [num(r['prediction_half_width']) for r in band], s)
            row += [f'{interp(mx, my, s):.3f}', f'{mean:.3f}', f'{half:.3f}']
        p = pred[test]
        row += [f"{float(p['rms_error']):.3f}", f"{float(p['rms_sd']):.3f}",
                f"{100 * float(p['inside_prediction_interval']):.0f}", p['specimens']]
        table.append(row)
    dr = [float(r[1]) for r in table]
    m400 = [float(r[9]) for r in table]  # at 380 kPa
    p400 = [float(r[10]) for r in table]
    sd = line_residual_sd(dr, m400)
    err = math.sqrt(sum((a - b) ** 2 for a, b in zip(p400, m400)) / len(m400))
    print('# Karlsruhe fine sand: blind predictions of the oedometer tests OE1-OE12 (Wichtmann & Triantafyllidis 2016,')
    print('# Acta Geotechnica 11:739-761; measured curves in assets/validation/karlsruhe_fine_sand_oedometer.csv), made by')
    print('# SimSols with the material calibrated on the triaxial tests (calibrated.toml) before the measured curves were')
    print('# compared. Axial strain eps1 in %, counted from sigma1 = 25 kPa; meas: the test, pred: the mean of the specimens')
    print('# (periodic cells of 300 spheres), pi95: half the 95 % prediction interval of one more specimen. rms_error and')
    print('# band_sd over the loading branch (20 points, 20-407 kPa); inside: % of those measured points inside the interval')
    print('# (a point above a specimen\'s last row, 388-405 kPa, counts as outside).')
    print(f'# At 380 kPa: r.m.s. prediction error {err:.3f} %; the tests\' own scatter (residual sd of the measured strain')
    print(f'# about a straight line in D_r) {sd:.3f} %.')
    print('test,Dr_pct,e0,eps_meas_100kPa,eps_pred_100kPa,pi95_100kPa,eps_meas_200kPa,eps_pred_200kPa,pi95_200kPa,'
          'eps_meas_380kPa,eps_pred_380kPa,pi95_380kPa,rms_error_pct,band_sd_pct,inside_pct,specimens')
    for r in table:
        print(','.join(r))


if __name__ == '__main__':
    main()
