#!/usr/bin/env python3
"""The preparation friction of each KFS test's specimen, from its relative density.

A sand's relative density D_r = (e_max - e) / (e_max - e_min) is carried over
to the spheres: the cell's own e_min and e_max are the void ratios after
isotropic compression to 100 kPa with a preparation friction of 0 (the
densest random packing) and of 1.0 (the loosest this preparation reaches),
from packing.csv. A test of D_r gets the spheres' e = e_max - D_r (e_max -
e_min), and the preparation friction that gives it, interpolated linearly
in packing.csv's means.

  density_map.py                 the table of the triaxial tests (kfs_triaxial.toml)
  density_map.py --oedometer     the table of the oedometer tests OE1-OE12, whose D_r is
                                 their initial void ratio's with the sand's e_max = 1.054 and
                                 e_min = 0.677 (the data set's header)
  density_map.py --check FILE    exit 1 unless FILE sets those frictions (to 1e-3; both tables)
  density_map.py --run SIMSOLS   measure packing.csv again (21 runs, ~15 min on 2 cores)
"""
import csv, os, re, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, '..', '..', 'validation', 'karlsruhe_fine_sand_triaxial_100kPa.csv')
OEDOMETER = os.path.join(HERE, '..', '..', 'validation', 'karlsruhe_fine_sand_oedometer.csv')
E_MAX_SAND, E_MIN_SAND = 1.054, 0.677
FRICTIONS = [0, 0.05, 0.1, 0.2, 0.3, 0.5, 1.0]


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith('#')))


def packing():
    by = {}
    for r in rows(os.path.join(HERE, 'packing.csv')):
        by.setdefault(float(r['preparation_friction']), []).append(1 / float(r['solid_fraction']) - 1)
    return sorted((mu, sum(e) / len(e)) for mu, e in by.items())


def friction_for(e, table):
    for (m0, e0), (m1, e1) in zip(table, table[1:]):
        if min(e0, e1) <= e <= max(e0, e1):
            return m0 + (m1 - m0) * (e - e0) / (e1 - e0)
    raise SystemExit(f'e = {e:.4f} is outside the packings of packing.csv')


def tests():
    seen = {}
    for r in rows(DATA):
        seen.setdefault(r['test_id'], (float(r['e0']), float(r['Dr0_pct']) / 100))
    return seen


def oedometer_tests():
    seen = {}
    for r in rows(OEDOMETER):
        if r['step'] == '0':
            e0 = float(r['e'])
            seen[r['test_id']] = (e0, (E_MAX_SAND - e0) / (E_MAX_SAND - E_MIN_SAND))
    return seen


def mapping(which=tests):
    table = packing()
    e_min, e_max = table[0][1], table[-1][1]
    out = []
    for name, (e_sand, dr) in which().items():
        e = e_max - dr * (e_max - e_min)
        out.append((name, e_sand, dr, e, round(friction_for(e, table), 3)))
    return e_min, e_max, out


def run(simsols):
    scene = open(os.path.join(HERE, 'kfs_cell.toml')).read().replace('test = "triaxial"', 'test = "isotropic"')
    lines = ['# Solid fraction of the KFS cell (kfs_cell.toml, test = "isotropic") compressed to 100 kPa against '
             'its preparation friction,', '# no rolling resistance while compressed; three specimens each. Made by '
             'density_map.py --run (docs/calibration.md).', 'preparation_friction,seed,solid_fraction']
    with tempfile.TemporaryDirectory() as tmp:
        for mu in FRICTIONS:
            for seed in (1, 2, 3):
                text = re.sub(r'(?m)^preparation_friction = .*$', f'preparation_friction = {mu}', scene)
                text = re.sub(r'(?m)^seed = .*$', f'seed = {seed}', text)
                path, out = os.path.join(tmp, 'iso.toml'), os.path.join(tmp, f'iso_{mu}_{seed}')
                open(path, 'w').write(text)
                subprocess.run([simsols, 'run', path, '--out', out, '-q'], check=True, stdout=subprocess.DEVNULL)
                summary = dict(l.split(' = ', 1) for l in open(os.path.join(out, 'summary.txt')).read().splitlines()
                               if ' = ' in l)
                lines.append(f'{mu},{seed},{summary["solid_fraction_compressed"].strip()}')
    open(os.path.join(HERE, 'packing.csv'), 'w').write('\n'.join(lines) + '\n')


def main():
    if len(sys.argv) == 3 and sys.argv[1] == '--run':
        run(sys.argv[2])
    e_min, e_max, out = mapping()
    if len(sys.argv) == 3 and sys.argv[1] == '--check':
        text = open(sys.argv[2]).read()
        bad = []
        listed = [t for t in out + mapping(oedometer_tests)[2] if 'name = "%s"' % t[0] in text]
        for name, _, _, _, mu in listed:
            m = re.search(r'name = "%s"\n(?:.|\n)*?"periodic_cell\.preparation_friction" = ([0-9.]+)' % name, text)
            if not m or abs(float(m.group(1)) - mu) > 1e-3:
                bad.append(f'{name}: {m.group(1) if m else "none"} in the file, {mu} from packing.csv')
        print('\n'.join(bad) or 'the preparation frictions agree with packing.csv')
        sys.exit(1 if bad else 0)
    if '--oedometer' in sys.argv:
        e_min, e_max, out = mapping(oedometer_tests)
    print(f'spheres: e_min = {e_min:.4f} (friction 0), e_max = {e_max:.4f} (friction 1.0)')
    print('| test | e (sand) | D_r | e (spheres) | preparation friction |\n|---|---|---|---|---|')
    for name, e_sand, dr, e, mu in out:
        print(f'| {name} | {e_sand:.4f} | {100 * dr:.1f} % | {e:.4f} | {mu} |')


if __name__ == '__main__':
    main()
