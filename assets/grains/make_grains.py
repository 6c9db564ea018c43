#!/usr/bin/env python3
"""Writes the grain meshes of assets/grains (README.md there): run once, from
this folder, with python3 and nothing else. Coordinates are whole multiples of
10 nm, so the hull and the volumes are computed exactly, in integers."""
import math
import random
from fractions import Fraction
from itertools import combinations

UNIT = 10**8  # coordinates are integers of 1e-8 m


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def hull(points):
    """Convex hull faces (i, j, k), counter-clockwise seen from outside, by
    trying every triple: fine for a few dozen points in general position."""
    faces = []
    for i, j, k in combinations(range(len(points)), 3):
        n = cross(sub(points[j], points[i]), sub(points[k], points[i]))
        d = [dot(n, sub(p, points[i])) for m, p in enumerate(points) if m not in (i, j, k)]
        assert all(x != 0 for x in d), "four coplanar points: pick another seed"
        if all(x < 0 for x in d):
            faces.append((i, j, k))
        elif all(x > 0 for x in d):
            faces.append((i, k, j))
    return faces


def volume(points, faces):
    """Exact enclosed volume in m^3 (divergence theorem, tetrahedra from 0)."""
    six_v = sum(dot(points[a], cross(points[b], points[c])) for a, b, c in faces)
    return Fraction(six_v, 6 * UNIT**3)


def text(n):
    return f"{'-' if n < 0 else ''}{abs(n) // UNIT}.{abs(n) % UNIT:08d}"


def write_stl(path, name, points, faces):
    with open(path, "w") as f:
        f.write(f"solid {name}\n")
        for a, b, c in faces:
            n = cross(sub(points[b], points[a]), sub(points[c], points[a]))
            length = math.sqrt(dot(n, n))
            f.write("  facet normal " + " ".join(f"{x / length:.6f}" for x in n) + "\n    outer loop\n")
            for v in (a, b, c):
                f.write("      vertex " + " ".join(text(x) for x in points[v]) + "\n")
            f.write("    endloop\n  endfacet\n")
        f.write(f"endsolid {name}\n")


def write_obj(path, comment, points, faces):
    with open(path, "w") as f:
        f.write(f"# {comment}\n")
        for p in points:
            f.write("v " + " ".join(text(x) for x in p) + "\n")
        for a, b, c in faces:
            f.write(f"f {a + 1} {b + 1} {c + 1}\n")


def sand_grain(seed=7, count=26, axes=(0.55e-3, 0.45e-3, 0.38e-3)):
    """Points at random directions on a squashed ellipsoid, each pulled in by
    up to 15 %: their hull is an angular, sand-like polyhedron."""
    rng = random.Random(seed)
    points = []
    for _ in range(count):
        z = 2 * rng.random() - 1
        phi = 2 * math.pi * rng.random()
        pull = 1 - 0.15 * rng.random()
        r = math.sqrt(1 - z * z)
        u = (r * math.cos(phi), r * math.sin(phi), z)
        points.append([round(pull * u[i] * axes[i] * UNIT) for i in range(3)])
    faces = hull(points)
    used = sorted({v for f in faces for v in f})  # drop the points inside the hull
    renumber = {v: n for n, v in enumerate(used)}
    return [points[v] for v in used], [tuple(renumber[v] for v in f) for f in faces]


def report(name, points, faces):
    v = volume(points, faces)
    lo = [min(p[i] for p in points) / UNIT for i in range(3)]
    hi = [max(p[i] for p in points) / UNIT for i in range(3)]
    print(f"{name}: {len(points)} vertices, {len(faces)} triangles, volume {float(v):.10e} m^3 (= {v}),"
          f" box {[f'{h - l:.6e}' for l, h in zip(lo, hi)]} m")


if __name__ == "__main__":
    points, faces = sand_grain()
    write_stl("sand_grain.stl", "sand_grain", points, faces)
    report("sand_grain.stl", points, faces)
    a = 25000  # 0.25 mm
    tet = [[a, a, a], [a, -a, -a], [-a, a, -a], [-a, -a, a]]
    tet_faces = hull(tet)
    write_obj("tetrahedron.obj", "A regular tetrahedron, corners (+-0.25, +-0.25, +-0.25) mm with an even count of"
              " minus signs, in metres (assets/grains/README.md)", tet, tet_faces)
    report("tetrahedron.obj", tet, tet_faces)
