#!/usr/bin/env python3
"""LIGGGHTS inputs for a SimSols shear-box scene (plain Python 3.11, no numpy).

    gen.py SCENE_RESOLVED_TOML OUTDIR

Reads a scene written by SimSols with all particles explicit (the
scene.resolved.toml of a `simsols run` or `simsols campaign` folder) and
writes into OUTDIR:

  particles.data   the beads (LIGGGHTS read_data, atom_style granular)
  lower.stl        the lower half: floor, four side plates, lower frame
  upper.stl        the upper half: four side plates, upper frame
  platen.stl       the platen, at z = 0 (placed by the input at run time)
  params.in        every number the input script uses (variables)

The walls are the twelve rectangles of solver/apparatus/shear_box/shear_box.cpp, each as two
triangles; the programme's numbers (time step, servo gains, check
intervals, criteria) follow solver/apparatus/shear_box/shear_programme.cpp and solver/contact_model.cpp.
"""
import math
import os
import sys
import tomllib


def simulate_restitution(gamma, h=1e-4):
    """SimSols' dimensionless Hertz impact with a delta^1/4 dashpot
    (solver/scene/contact_model.cpp): x'' = -max(0, x^1.5 + gamma x^0.25 x')."""

    def rhs(x, v):
        x = max(x, 0.0)
        sx = math.sqrt(x)
        return v, -max(x * sx + gamma * math.sqrt(sx) * v, 0.0)

    x, v = 0.0, 1.0
    for i in range(10_000_000):
        k1 = rhs(x, v)
        k2 = rhs(x + 0.5 * h * k1[0], v + 0.5 * h * k1[1])
        k3 = rhs(x + 0.5 * h * k2[0], v + 0.5 * h * k2[1])
        k4 = rhs(x + h * k3[0], v + h * k3[1])
        nx = x + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        nv = v + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        if i > 0 and nx <= 0.0:
            return -nv
        x, v = nx, nv
        if v < 0 and rhs(x, v)[1] >= 0:
            return -v
    return -v


def damping_for_restitution(e):
    if e >= 1.0:
        return 0.0
    lo, hi = 0.0, 1.0
    while simulate_restitution(hi) > e:
        hi *= 2.0
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        if simulate_restitution(mid) > e:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-7 * hi:
            break
    return 0.5 * (lo + hi)


def liggghts_restitution(gamma):
    """The coefficientRestitution that makes LIGGGHTS' hertz dashpot
    2 sqrt(5/6) beta sqrt(Sn m*) (Sn = 2 E* sqrt(R* delta)) equal SimSols'
    gamma sqrt(m* Kn) delta^1/4 (Kn = 4/3 E* sqrt(R*)): sqrt(5) |beta| = gamma,
    beta = ln e / sqrt(ln^2 e + pi^2)."""
    b = gamma / math.sqrt(5.0)
    return math.exp(-math.pi * b / math.sqrt(1.0 - b * b))


def tri_rect(centre, u, v, hu, hv):
    """Two triangles of the rectangle centre +- hu u +- hv v."""
    c = [centre[k] for k in range(3)]
    p = lambda a, b: [c[k] + a * hu * u[k] + b * hv * v[k] for k in range(3)]
    a, b, cc, d = p(-1, -1), p(1, -1), p(1, 1), p(-1, 1)
    return [(a, b, cc), (a, cc, d)]


def write_stl(path, name, rects):
    with open(path, "w") as f:
        f.write(f"solid {name}\n")
        for r in rects:
            for t in tri_rect(*r):
                e1 = [t[1][k] - t[0][k] for k in range(3)]
                e2 = [t[2][k] - t[0][k] for k in range(3)]
                n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                     e1[0] * e2[1] - e1[1] * e2[0]]
                ln = math.sqrt(sum(x * x for x in n)) or 1.0
                f.write("  facet normal %.9e %.9e %.9e\n    outer loop\n" % tuple(x / ln for x in n))
                for q in t:
                    f.write("      vertex %.12e %.12e %.12e\n" % tuple(q))
                f.write("    endloop\n  endfacet\n")
        f.write(f"endsolid {name}\n")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    src, out = sys.argv[1], sys.argv[2]
    with open(src, "rb") as f:
        scene = tomllib.load(f)
    os.makedirs(out, exist_ok=True)
    mats = {m["name"]: m for m in scene["materials"]}
    box = scene["shear_box"]
    parts = scene["particles"]
    if not parts:
        sys.exit("the scene lists no particles (use a scene.resolved.toml)")
    glass = mats[parts[0]["material"]]
    steel = mats[box["wall_material"]]
    if any(p["material"] != parts[0]["material"] for p in parts):
        sys.exit("one bead material only")
    L, W = box["length"], box["width"]
    zs, g = box["split_height"], box["gap"]
    travel = box["shear_displacement"]
    r_max = max(p["radius"] for p in parts)
    top = max(p["position"][2] + p["radius"] for p in parts)

    # Time step: dt_fraction x the Rayleigh step of the smallest bead.
    num = scene["numerics"]
    if num.get("dt", 0) > 0:
        dt = num["dt"]
    else:
        dt_r = min(math.pi * p["radius"] * math.sqrt(
            mats[p["material"]]["density"] /
            (mats[p["material"]]["young_modulus"] / (2 * (1 + mats[p["material"]]["poisson_ratio"]))))
                   / (0.1631 * mats[p["material"]]["poisson_ratio"] + 0.8766) for p in parts)
        dt = num["dt_fraction"] * dt_r

    # Walls (solver/apparatus/shear_box/shear_box.cpp).
    platen_z = top + 0.1 * 2 * r_max
    upper_top = platen_z + 4 * r_max + 0.5 * travel
    low_h, up_lo = zs - g / 2, zs + g / 2
    up_h = upper_top - up_lo
    frame = travel + 2 * r_max
    ex, ey, ez = (1, 0, 0), (0, 1, 0), (0, 0, 1)
    lower = [((L / 2, W / 2, 0), ex, ey, L / 2, W / 2),              # floor
             ((0, W / 2, low_h / 2), ey, ez, W / 2, low_h / 2),      # lower_x0
             ((L, W / 2, low_h / 2), ey, ez, W / 2, low_h / 2),      # lower_x1
             ((L / 2, 0, low_h / 2), ex, ez, L / 2, low_h / 2),      # lower_y0
             ((L / 2, W, low_h / 2), ex, ez, L / 2, low_h / 2),      # lower_y1
             ((-frame / 2, W / 2, zs - g / 2), ex, ey, frame / 2, W / 2)]  # lower_frame
    zu = up_lo + up_h / 2
    upper = [((0, W / 2, zu), ey, ez, W / 2, up_h / 2),              # upper_x0
             ((L, W / 2, zu), ey, ez, W / 2, up_h / 2),              # upper_x1
             ((L / 2, 0, zu), ex, ez, L / 2, up_h / 2),              # upper_y0
             ((L / 2, W, zu), ex, ez, L / 2, up_h / 2),              # upper_y1
             ((L + frame / 2, W / 2, zs + g / 2), ex, ey, frame / 2, W / 2)]  # upper_frame
    write_stl(os.path.join(out, "lower.stl"), "lower", lower)
    write_stl(os.path.join(out, "upper.stl"), "upper", upper)
    write_stl(os.path.join(out, "platen.stl"), "platen", [((L / 2, W / 2, 0), ex, ey, L / 2, W / 2)])

    # Simulation domain: the box, its frames and travel, with a margin.
    m = 2 * r_max
    lo = (-frame - travel - m, -m, -m)
    hi = (L + frame + travel + m, W + m, upper_top + m)
    with open(os.path.join(out, "particles.data"), "w") as f:
        f.write(f"SimSols beads from {os.path.basename(src)}\n\n{len(parts)} atoms\n2 atom types\n\n")
        f.write("%.12e %.12e xlo xhi\n%.12e %.12e ylo yhi\n%.12e %.12e zlo zhi\n\nAtoms\n\n"
                % (lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]))
        for i, p in enumerate(parts, 1):
            x, y, z = p["position"]
            f.write("%d 1 %.12e %.6f %.15e %.15e %.15e\n"
                    % (i, 2 * p["radius"], mats[p["material"]]["density"], x, y, z))

    # Pair constants (solver/scene/contact_model.cpp): restitution the mean,
    # friction the smaller of the two materials.
    e_gg = glass["restitution"]
    e_gs = 0.5 * (glass["restitution"] + steel["restitution"])
    e_ss = steel["restitution"]
    gam = {e: damping_for_restitution(e) for e in {e_gg, e_gs, e_ss}}
    mu = lambda a, b: min(a["sliding_friction"], b["sliding_friction"])
    mur = lambda a, b: min(a["rolling_friction"], b["rolling_friction"])
    r = parts[0]["radius"]
    # LIGGGHTS' rolling coefficient is dimensionless: torque limit mu_r' |Fn| R*.
    # SimSols' mu_r is a length: torque limit mu_r |Fn|. So mu_r' = mu_r / R*,
    # R* = R/2 for two beads, R for a bead on a wall.
    rr_gg = mur(glass, glass) / (r / 2)
    rr_gs = mur(glass, steel) / r
    rr_ss = rr_gs

    # Servo (solver/apparatus/shear_box/shear_programme.cpp, tune_servo): gain from the Hertz
    # stiffness of the platen's contacts at the target stress.
    sigma = box["normal_stress"]
    area = L * W
    d = 2 * r
    e_star_gs = 1 / ((1 - glass["poisson_ratio"] ** 2) / glass["young_modulus"] +
                     (1 - steel["poisson_ratio"] ** 2) / steel["young_modulus"])
    k_hertz = 4 / 3 * e_star_gs * math.sqrt(d / 2)
    contacts = area / d ** 2
    k_contact = 1.5 * (sigma * d * d) ** (1 / 3) * k_hertz ** (2 / 3)
    k_platen = contacts * k_contact
    gain = box["servo_gain"] if box["servo_gain"] > 0 else 0.5 / (k_platen * dt)
    bead_mass = glass["density"] * 4 / 3 * math.pi * r ** 3
    mass = bead_mass * len(parts)
    layers = max(1.0, top / d)
    period = 2 * math.pi * math.sqrt(mass / (k_platen / layers))
    t_i = box["servo_integral_time"] if box["servo_integral_time"] > 0 else 5 * period
    f_target = sigma * area
    vmax = box["servo_max_speed"]
    kp = gain * f_target / vmax          # LIGGGHTS: v = vmax (kp e + ki sum e dt) / F_target
    ki = kp / t_i
    check = max(50, round(0.5e-3 / dt))  # steps between the phase checks
    settle_steps = max(1, round(box["settle_time"] / dt))
    consolidate_steps = max(1, round(box["consolidate_time"] / dt))

    v = {
        "dt": dt, "nbeads": len(parts), "d": d, "rbead": r, "rho": glass["density"],
        "boxL": L, "boxW": W, "area": area, "split": zs, "gap": g,
        "platen_z0": platen_z, "top0": top,
        "E_glass": glass["young_modulus"], "E_steel": steel["young_modulus"],
        "nu_glass": glass["poisson_ratio"], "nu_steel": steel["poisson_ratio"],
        "rho_steel": steel["density"],
        "e_gg": liggghts_restitution(gam[e_gg]), "e_gs": liggghts_restitution(gam[e_gs]),
        "e_ss": liggghts_restitution(gam[e_ss]),
        "mu_gg": mu(glass, glass), "mu_gs": mu(glass, steel), "mu_ss": mu(steel, steel),
        "rr_gg": rr_gg, "rr_gs": rr_gs, "rr_ss": rr_ss,
        "gravity": -scene["effects"]["gravity"][2],
        "sigma": sigma, "f_target": f_target, "vmax": vmax, "kp": kp, "ki": ki,
        "inertial": box["inertial_number"], "travel": travel, "rows": box["rows"],
        "check": check, "settle_steps": settle_steps, "consolidate_steps": consolidate_steps,
        "ke_settle": 1e-4 * len(parts) * bead_mass * 9.81 * d,
        "bead_mass": bead_mass, "skin": 0.1 * d,
    }
    with open(os.path.join(out, "params.in"), "w") as f:
        f.write(f"# written by gen.py from {src}\n")
        f.write(f"# SimSols damping gamma: {', '.join('e=%g: %.6f' % kv for kv in sorted(gam.items()))}\n")
        f.write(f"# servo: gain {gain:.6e} m/(s N), integral time {t_i:.6e} s\n")
        for k, val in v.items():
            f.write(f"variable {k} equal {val:.12g}\n" if isinstance(val, float) else
                    f"variable {k} equal {val}\n")
    print(f"gen.py: {len(parts)} beads, dt = {dt:.6e} s, top = {top * 1e3:.4f} mm, "
          f"split = {zs * 1e3:.4f} mm, gap = {g * 1e3:.4f} mm, "
          f"gamma = {gam[e_gg]:.5f} (LIGGGHTS e = {v['e_gg']:.5f}), kp = {kp:.4f}, ki = {ki:.4g} 1/s")


if __name__ == "__main__":
    main()
