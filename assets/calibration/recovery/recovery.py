#!/usr/bin/env python3
"""Two-parameter recovery study of `simsols calibrate` (docs/calibration.md, "Recovery").

  recovery.py OUT [--simsols build/release/app/simsols] > recovery.csv
  recovery.py OUT --budget 32 --rounds 4 --truths 2 > recovery_budget32.csv

For each known material (TRUTHS: sliding friction mu_s and rolling lever
arm mu_r), the program makes its own "measurements": `simsols predict`
with the truth as the calibrated values runs recovery_cell.toml at three
densities (preparation frictions 0.5, 0.15, 0) on specimens it alone uses
(seeds 2001, 2002). Then `simsols calibrate`, told only the ranges (mu_s
0.1-1, mu_r 1e-5 to 5e-4 m, log), fits both parameters to the stress ratio
and volumetric strain of the three tests of one specimen seed, once with
specimen 2001's curves as the measurements and once with 2002's. Printed:
one row per truth, measured specimen and parameter, with the calibrated
value, the posterior mean and 95 % interval, and whether the truth lies
inside. --budget and --rounds change the calibration's (16 designs in 2
rounds by default; another budget runs in folders of its own), --truths
picks truths by number. Everything is kept in OUT; running again resumes.
"""
import argparse, csv, os, subprocess, sys

TRUTHS = [(0.2, 3e-5), (0.3, 2e-4), (0.5, 8e-5), (0.7, 3e-4)]
KEYS = {'mu_s': 'materials.beads.sliding_friction', 'mu_r': 'materials.beads.rolling_friction'}
SEEDS = (2001, 2002)  # the measured specimens (simsols predict's seeds)
DENSITIES = [('loose', 0.5), ('medium', 0.15), ('dense', 0.0)]
HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, 'recovery_cell.toml')

Y = ('[[{t}.y]]\ncolumn = "stress_ratio"\nunit = "-"\nquantity = "stress_ratio"\n'
     '[[{t}.y]]\ncolumn = "volumetric_strain"\nunit = "-"\nquantity = "volumetric_strain"\n')
X = 'x = { column = "strain", unit = "-", quantity = "axial_strain" }\n'


def write(path, text):
    with open(path + '.tmp', 'w') as f:
        f.write(text)
    os.replace(path + '.tmp', path)


def measurements(simsols, d, truth):
    write(os.path.join(d, 'truth.toml'),
          '[calibrated]\n' + ''.join(f"'{KEYS[n]}' = {v!r}\n" for n, v in zip(KEYS, truth)))
    text = '[prediction]\nname = "truth"\ncalibrated = "truth.toml"\nspecimens = 2\npoints = 10\n'
    for name, prep in DENSITIES:
        text += (f'\n[[tests]]\nname = "{name}"\nscene = "{SCENE}"\n'
                 f'set = {{ "periodic_cell.preparation_friction" = {prep} }}\n' + X + Y.format(t='tests'))
    write(os.path.join(d, 'truth_predict.toml'), text)
    subprocess.run([simsols, 'predict', os.path.join(d, 'truth_predict.toml'), '--out',
                    os.path.join(d, 'measured'), '-q'], check=True, stdout=subprocess.DEVNULL)


def calibrate(simsols, d, seed, budget, rounds):
    text = (f'[calibration]\nname = "recovery"\nbudget = {budget}\nrounds = {rounds}\nreplicates = 3\npoints = 10\n'
            '\n[[parameters]]\nname = "mu_s"\nkey = "%s"\nmin = 0.1\nmax = 1.0\n'
            '\n[[parameters]]\nname = "mu_r"\nkey = "%s"\nmin = 1e-5\nmax = 5e-4\nscale = "log"\n'
            % (KEYS['mu_s'], KEYS['mu_r']))
    folder = f'calibration_s{seed}' + ('' if (budget, rounds) == (16, 2) else f'_b{budget}r{rounds}')
    for name, prep in DENSITIES:
        text += (f'\n[[targets]]\nname = "{name}"\nscene = "{SCENE}"\n'
                 f'data = "measured/{name}/s{seed}/cell.csv"\nwhere = "stage=1"\n'
                 f'set = {{ "periodic_cell.preparation_friction" = {prep} }}\n' + X + Y.format(t='targets'))
    write(os.path.join(d, folder + '.toml'), text)
    out = os.path.join(d, folder)
    subprocess.run([simsols, 'calibrate', os.path.join(d, folder + '.toml'), '--out', out, '-q'],
                   check=True, stdout=subprocess.DEVNULL)
    return {r['parameter']: r for r in csv.DictReader(open(os.path.join(out, 'parameters.csv')))}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('out')
    ap.add_argument('--simsols', default='build/release/app/simsols')
    ap.add_argument('--budget', type=int, default=16)
    ap.add_argument('--rounds', type=int, default=2)
    ap.add_argument('--truths', default=','.join(str(k + 1) for k in range(len(TRUTHS))))
    a = ap.parse_args()
    picked = [int(k) for k in a.truths.split(',')]
    print('# Two-parameter recovery of simsols calibrate (assets/calibration/recovery/recovery.py, docs/calibration.md):')
    print('# targets made by the program with the true values (recovery_cell.toml, three densities, one specimen seed),')
    print(f'# fitted over mu_s in [0.1, 1] and mu_r in [1e-5, 5e-4] m (log); {a.budget} designs in {a.rounds} rounds, 3 replicates.')
    print('# mu_r in m (d = 1 mm); inside: the truth lies in the 95 % interval (1) or not (0).')
    print('truth,specimen,designs,parameter,true,calibrated,mean,lo95,hi95,inside')
    for k, truth in enumerate(TRUTHS):
        if k + 1 not in picked:
            continue
        d = os.path.abspath(os.path.join(a.out, f'truth{k + 1}'))
        os.makedirs(d, exist_ok=True)
        print(f'[recovery] truth {k + 1}/{len(TRUTHS)}: mu_s = {truth[0]}, mu_r = {truth[1]} m', file=sys.stderr)
        measurements(a.simsols, d, truth)
        for seed in SEEDS:
            p = calibrate(a.simsols, d, seed, a.budget, a.rounds)
            for name, v in zip(KEYS, truth):
                r = p[name]
                inside = int(float(r['lo95']) <= v <= float(r['hi95']))
                print(f"{k + 1},{seed},{a.budget},{name},{v:.6g},{float(r['calibrated']):.4g},{float(r['mean']):.4g},"
                      f"{float(r['lo95']):.4g},{float(r['hi95']):.4g},{inside}", flush=True)


if __name__ == '__main__':
    main()
