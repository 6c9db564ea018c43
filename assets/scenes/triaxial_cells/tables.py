#!/usr/bin/env python3
"""The rigid and the membrane triaxial cell on the same specimens
(docs/triaxial.md, "The membrane cell"), from the runs' summary.txt and
triaxial.csv.

Each seed's specimen is run in both cells (the scenes differ only in
`cell`; the specimen is poured and consolidated by the plates in both):

    for s in 1 2 3 4 5; do
      sed "s/^seed = 1/seed = $s/" assets/scenes/triaxial.toml > rigid.toml
      sed "s/^seed = 1/seed = $s/" assets/scenes/triaxial_cells/membrane.toml > membrane.toml
      simsols run rigid.toml --out RUNS/rigid/s$s -q
      simsols run membrane.toml --out RUNS/membrane/s$s -q
      sed 's/^cell = "membrane".*/cell = "membrane"\nmembrane_spacing = 0.25/' membrane.toml > fine.toml
      simsols run fine.toml --out RUNS/membrane_fine/s$s -q
    done
    python3 assets/scenes/triaxial_cells/tables.py RUNS

and, for the dense specimen of dense_rigid.toml and dense_membrane.toml
(one run each, "A dense, rougher specimen"),

    python3 assets/scenes/triaxial_cells/tables.py --dense RIGID_DIR MEMBRANE_DIR

writes docs/img/triaxial_dense_x2.csv and prints the docs' table.

writes docs/img/triaxial_cells_tests.csv (every test) and
docs/img/triaxial_cells.csv (each cell's mean with its 95 % interval over
the seeds, and the membrane's paired change, membrane - rigid, seed by
seed, and the finer membrane's, membrane_fine - membrane; a cell whose
folder is missing is left out). tests/layout/check_triaxial_cells_tables.py checks the docs' table
against both, the means and intervals recomputed from the tests.
"""
import csv
import os
import sys

# the mean and Student's 95 % interval, as the docs' table checks compute them
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                                "tests", "layout"))
from ensemble_stats import mean_ci  # noqa: E402

CELLS = ["rigid", "membrane", "membrane_fine"]  # membrane_fine: membrane_spacing = 0.25
PAIRS = [("membrane", "rigid"), ("membrane_fine", "membrane"),  # paired changes, seed by seed
         ("membrane_fine", "rigid")]
# column of the tables, key of summary.txt (None: from triaxial.csv)
MEASURES = [("initial_void_ratio", "initial_void_ratio"),
            ("peak_deg", "peak_friction_angle_deg"),
            ("peak_axial_strain", "peak_axial_strain"),
            ("critical_deg", "critical_friction_angle_deg"),
            ("critical_void_ratio", "critical_void_ratio"),
            ("max_dilatancy_deg", "max_dilatancy_angle_deg"),
            ("final_volumetric_strain", None),
            ("median_wall_internal_gap_percent", "median_wall_internal_gap_percent"),
            # the membrane's share of the platen's stress at the end, measured
            # and as the shell estimate gives it (0 in the rigid cell)
            ("end_membrane_axial_kPa", "end_membrane_axial_kPa"),
            ("end_membrane_shell_kPa", "end_membrane_shell_kPa")]


def summary(path):
    out = {}
    for line in open(path):
        if "=" in line and not line.startswith("#"):
            k, v = line.split("=", 1)
            out[k.strip()] = v.strip()
    return out


def final_volumetric_strain(path):
    rows = list(csv.DictReader(open(path)))
    return float(rows[-1]["volumetric_strain"])


def measured(d):
    """One run's MEASURES, rounded as written: an ensemble is of what the table shows."""
    s = summary(os.path.join(d, "summary.txt"))
    row = {}
    for col, key in MEASURES:
        v = final_volumetric_strain(os.path.join(d, "triaxial.csv")) if key is None else float(s.get(key, 0))
        row[col] = round(v, DIGITS[col])
    return row


def tests(runs):
    out = []
    for cell in CELLS:
        if not os.path.isdir(os.path.join(runs, cell)):
            continue
        for seed_dir in sorted(os.listdir(os.path.join(runs, cell))):
            d = os.path.join(runs, cell, seed_dir)
            if not os.path.exists(os.path.join(d, "summary.txt")):
                continue
            out.append({"cell": cell, "seed": seed_dir.lstrip("s"), **measured(d)})
    return out


def fmt(v, digits):
    return f"{v:.{digits}f}"


DIGITS = {"initial_void_ratio": 3, "peak_deg": 2, "peak_axial_strain": 3, "critical_deg": 2,
          "critical_void_ratio": 3, "max_dilatancy_deg": 2, "final_volumetric_strain": 4,
          "median_wall_internal_gap_percent": 2, "end_membrane_axial_kPa": 2,
          "end_membrane_shell_kPa": 2}


def ensemble(rows):
    """Each cell's mean and interval, and the paired changes (PAIRS)."""
    out = []
    by = {c: {r["seed"]: r for r in rows if r["cell"] == c} for c in CELLS}
    cells = [c for c in CELLS if by[c]]
    seeds = sorted(set.intersection(*(set(by[c]) for c in cells)), key=int)
    pairs = [p for p in PAIRS if p[0] in cells and p[1] in cells]
    for cell in cells + [f"{a} - {b}" for a, b in pairs]:
        row = {"cell": cell, "specimens": len(seeds)}
        for col, _ in MEASURES:
            if " - " in cell:
                a, b = cell.split(" - ")
                values = [by[a][s][col] - by[b][s][col] for s in seeds]
            else:
                values = [by[cell][s][col] for s in seeds]
            m, ci = mean_ci(values)
            row[col] = fmt(m, DIGITS[col])
            row[col + "_ci95"] = fmt(ci, DIGITS[col])
        out.append(row)
    return out


def write(path, rows, header):
    with open(path, "w", newline="") as f:
        f.write(header)
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def dense(rigid_dir, membrane_dir, root):
    """One specimen in each cell (dense_rigid.toml, dense_membrane.toml): an
    example, no interval; docs/img/triaxial_dense_x2.csv and the docs' table."""
    rows = [{"cell": cell, **{k: fmt(v, DIGITS[k]) for k, v in measured(d).items()}}
            for cell, d in (("rigid", rigid_dir), ("membrane", membrane_dir))]
    write(os.path.join(root, "docs/img/triaxial_dense_x2.csv"), rows,
          "# One dense specimen of mu = 0.262 glass in each cell, L/d = 16 (docs/triaxial.md); "
          "angles in deg, strains as fractions, gap in % of p', shares in kPa; "
          "written by assets/scenes/triaxial_cells/tables.py --dense\n")
    print(DENSE_HEADER)
    for r in rows:
        print("| " + " | ".join(r[c] for c in DENSE_COLUMNS) + " |")


# the docs' dense table, as tests/layout/check_triaxial_cells_tables.py reads it
DENSE_COLUMNS = ["cell", "initial_void_ratio", "peak_deg", "peak_axial_strain", "critical_deg",
                 "max_dilatancy_deg", "final_volumetric_strain", "median_wall_internal_gap_percent",
                 "end_membrane_axial_kPa"]
DENSE_HEADER = ("| cell | e after consolidation | peak φ′ (°) | εa at peak | critical φ′ (°) | ψ max (°) "
                "| εv at the end | walls vs contacts, median (% of p′) | membrane's axial share at the end (kPa) |\n"
                "|---|---|---|---|---|---|---|---|---|")


def main():
    root = os.path.join(os.path.dirname(__file__), "..", "..", "..")
    if sys.argv[1] == "--dense":
        dense(sys.argv[2], sys.argv[3], root)
        return
    runs = sys.argv[1]
    rows = tests(runs)
    shown = [{k: (fmt(v, DIGITS[k]) if k in DIGITS else v) for k, v in r.items()} for r in rows]
    note = ("# Rigid and membrane triaxial cell, the same specimens (docs/triaxial.md); "
            "angles in deg, strains as fractions, gap in % of p', shares in kPa; "
            "written by assets/scenes/triaxial_cells/tables.py\n")
    write(os.path.join(root, "docs/img/triaxial_cells_tests.csv"), shown, note)
    table = ensemble(rows)
    write(os.path.join(root, "docs/img/triaxial_cells.csv"), table,
          note.replace("the same specimens", "means and 95 % t-intervals over the specimens"))
    # the docs' table, as tests/layout/check_triaxial_cells_tables.py reads it
    print("| cell | specimens | e after consolidation | peak φ′ (°) | εa at peak | critical φ′ (°) "
          "| e critical | ψ max (°) | εv at the end | walls vs contacts, median (% of p′) "
          "| membrane's axial share at the end (kPa) | shell estimate (kPa) |")
    print("|---" * 12 + "|")
    for r in table:
        print("| " + " | ".join([r["cell"], str(r["specimens"])] +
                                [f"{r[c]} ± {r[c + '_ci95']}" for c, _ in MEASURES]) + " |")


if __name__ == "__main__":
    main()
