#!/usr/bin/env python3
"""Tables of a LIGGGHTS shear run (plain Python 3).

    post.py OUTDIR [GEN_DIR]

Reads OUTDIR/rows.txt and OUTDIR/phases.txt (written by shear.in) and the
parameters in GEN_DIR/params.in (default OUTDIR/gen) and writes

  OUTDIR/liggghts_shear.csv   displacement_mm, tau_kPa, sigma_kPa,
                              tau_over_sigma, dilation_mm, then time_s, step,
                              shear_force_N, shear_force_upper_N,
                              normal_force_N, platen_z_mm, kinetic_energy_J,
                              bead_contacts_per_bead, outside
  OUTDIR/shear.csv            the same rows in SimSols' shear.csv layout
                              (solver/apparatus/shear_box/shear_programme.cpp, shear_rows_csv)
  OUTDIR/preparation.csv      settle and consolidation every check interval (from
                              log.liggghts): time, kinetic energies, top of the
                              highest bead, platen height and force (one step)
  OUTDIR/summary.txt          the preparation and the test in key = value lines

Forces are means over each row's steps; tau = T / A and sigma = N / A on the
nominal area A = length x width; dilation = platen rise since shearing began.
"""
import math
import os
import sys


def params(path):
    v = {}
    for line in open(path):
        f = line.split()
        if len(f) >= 4 and f[0] == "variable" and f[2] == "equal":
            v[f[1]] = float(f[3])
    return v


def phases(path):
    out = {}
    for line in open(path):
        f = line.split()
        if not f or f[0] == "phase":
            continue
        out[f[0]] = {f[i]: float(f[i + 1]) for i in range(1, len(f) - 1, 2)}
    return out


def preparation(log, out, r):
    """Thermo lines of the settle (6 columns) and consolidation (8 columns)
    runs of log.liggghts, each step once."""
    seen, lines = set(), []
    for line in open(log):
        f = line.split()
        if len(f) not in (6, 8) or not f[0].isdigit():
            continue
        try:
            v = [float(x) for x in f]
        except ValueError:
            continue
        if v[0] in seen:
            continue
        seen.add(v[0])
        lines.append(v)
    with open(os.path.join(out, "preparation.csv"), "w") as f:
        f.write("phase,time_s,step,kinetic_energy_J,rotational_energy_J,top_bead_mm,"
                "platen_z_mm,platen_force_N\n")
        for v in lines:
            if len(v) == 6:
                f.write("settle,%.9g,%d,%.6g,%.6g,%.9g,,\n" % (v[1], v[0], v[3], v[4], (v[5] + r) * 1e3))
            else:
                f.write("consolidate,%.9g,%d,%.6g,%.6g,%.9g,%.9g,%.9g\n" % (
                    v[1], v[0], v[3], v[4], (v[5] + r) * 1e3, v[7] * 1e3, v[6]))


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    out = sys.argv[1]
    gen = sys.argv[2] if len(sys.argv) == 3 else os.path.join(out, "gen")
    p = params(os.path.join(gen, "params.in"))
    ph = phases(os.path.join(out, "phases.txt"))
    area, sigma_t, d, rho, n = p["area"], p["sigma"], p["d"], p["rho"], p["nbeads"]
    z0 = ph["consolidated"]["height"]
    speed = ph["consolidated"]["speed"]
    if os.path.exists(os.path.join(out, "log.liggghts")):
        preparation(os.path.join(out, "log.liggghts"), out, p["rbead"])
    rows = []
    for line in open(os.path.join(out, "rows.txt")):
        if line.startswith("#") or not line.strip():
            continue
        t, step, dx, T, Tu, N, pz, ke, contacts, outside = (float(x) for x in line.split())
        rows.append(dict(t=t, step=int(step), dx=dx, T=T, Tu=Tu, N=N, pz=pz, ke=ke,
                         coord=contacts / n, outside=int(outside)))
    with open(os.path.join(out, "liggghts_shear.csv"), "w") as f:
        f.write("displacement_mm,tau_kPa,sigma_kPa,tau_over_sigma,dilation_mm,time_s,step,"
                "shear_force_N,shear_force_upper_N,normal_force_N,platen_z_mm,kinetic_energy_J,"
                "bead_contacts_per_bead,outside\n")
        for r in rows:
            tau, sig = r["T"] / area, r["N"] / area
            f.write("%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.6g,%d\n" % (
                r["dx"] * 1e3, tau * 1e-3, sig * 1e-3, tau / sig if sig > 0 else 0,
                (r["pz"] - z0) * 1e3, r["t"], r["step"], r["T"], r["Tu"], r["N"], r["pz"] * 1e3,
                r["ke"], r["coord"], r["outside"]))
    with open(os.path.join(out, "shear.csv"), "w") as f:
        f.write("time_s,step,displacement_mm,shear_force_N,shear_force_upper_N,tau_kPa,"
                "tau_corrected_kPa,normal_force_N,sigma_kPa,dilation_mm,tau_over_sigma,"
                "friction_angle_deg,coordination,kinetic_energy_J,inertial_number,outside\n")
        for r in rows:
            tau, sig = r["T"] / area, r["N"] / area
            corr = max(0.0, p["boxL"] - abs(r["dx"])) * p["boxW"]
            height = r["pz"]
            inertial = speed / height * d * math.sqrt(rho / sig) if sig > 0 else 0
            f.write("%.9g,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d\n" % (
                r["t"], r["step"], r["dx"] * 1e3, r["T"], r["Tu"], tau * 1e-3, r["T"] / corr * 1e-3,
                r["N"], sig * 1e-3, (r["pz"] - z0) * 1e3, tau / sig if sig > 0 else 0,
                math.degrees(math.atan(tau / sig)) if sig > 0 else 0, r["coord"], r["ke"],
                inertial, r["outside"]))
    sig = [r["N"] / area for r in rows]
    with open(os.path.join(out, "summary.txt"), "w") as f:
        f.write("normal_stress_kPa = %.6g\n" % (sigma_t * 1e-3))
        f.write("bead_diameter_mm = %.6g\n" % (d * 1e3))
        f.write("settled_top_mm = %.6g\n" % (ph["settled"]["top"] * 1e3))
        f.write("specimen_height_mm = %.6g\n" % (z0 * 1e3))
        f.write("shear_speed_mm_s = %.6g\n" % (speed * 1e3))
        f.write("row_steps = %d\n" % ph["consolidated"]["row_steps"])
        f.write("settle_time_s = %.6g\n" % ph["settled"]["time"])
        f.write("consolidate_time_s = %.6g\n" % (ph["consolidated"]["time"] - ph["settled"]["time"]))
        f.write("rows = %d\n" % len(rows))
        if rows:
            f.write("sheared_mm = %.6g\n" % (rows[-1]["dx"] * 1e3))
            f.write("sigma_min_kPa = %.6g\nsigma_max_kPa = %.6g\n" % (min(sig) * 1e-3, max(sig) * 1e-3))
            f.write("max_beads_outside = %d\n" % max(r["outside"] for r in rows))
            f.write("steps = %d\n" % rows[-1]["step"])
    print("post.py: %d rows, specimen height %.4f mm -> %s" % (
        len(rows), z0 * 1e3, os.path.join(out, "liggghts_shear.csv")))


if __name__ == "__main__":
    main()
