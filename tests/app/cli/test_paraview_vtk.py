"""A run's ParaView series read back with the VTK library (python3-vtk9).

Usage: test_paraview_vtk.py SIMSOLS SCENE WORK_DIR

Runs SCENE (two beads falling freely from rest, one resting on the floor)
with a dump every 2 ms, then once more stopped half way and resumed, and
checks what ParaView would show: the .pvd files index one .vtp per dump
at step x dt; every file reads with VTK's own XML reader; the falling beads
are where free fall puts them; the resting bead's floor contact carries
its weight, and the floor the opposite force; the resumed run's series is
the uninterrupted one's. Exit status 0 when all holds.
"""
import math
import pathlib
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

G = 9.81
RADIUS = 1e-3
DENSITY = 2500
DROP_FROM = 0.02  # m, the falling beads' centres at t = 0
DUMP = 0.002      # s
FAILURES = []


def check(ok, what):
    if not ok:
        FAILURES.append(what)
        print("FAIL:", what)


def scene_text(base):
    return base + f"""
[[particles]]
material = "glass"
radius = {RADIUS}
position = [0.01, 0, {RADIUS}]

[output]
dump_interval = {DUMP}
"""


def run(simsols, args):
    subprocess.run([simsols, "run", *args, "-q"], check=True, stdout=subprocess.DEVNULL)


def series(folder, kind):
    """The (time, file) entries of kind.pvd."""
    root = ET.parse(folder / "paraview" / f"{kind}.pvd").getroot()
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]


def read(folder, name):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(str(folder / "paraview" / name))
    reader.Update()
    data = reader.GetOutput()
    arrays = {}
    for attributes in (data.GetPointData(), data.GetCellData()):
        for i in range(attributes.GetNumberOfArrays()):
            arrays[attributes.GetArrayName(i)] = tuples(attributes.GetArray(i))
    points = [data.GetPoint(i) for i in range(data.GetNumberOfPoints())]
    time = data.GetFieldData().GetArray("TimeValue").GetValue(0)
    return data, points, arrays, time


def tuples(array):
    """A VTK array as a list of values (one component) or of tuples."""
    n, k = array.GetNumberOfTuples(), array.GetNumberOfComponents()
    return [array.GetTuple(i) if k > 1 else array.GetTuple1(i) for i in range(n)]


def check_dump(folder, time, files):
    particles, points, p, t = read(folder, files["particles"])
    check(t == time, f"{files['particles']}: TimeValue {t} against the .pvd's {time}")
    check(particles.GetNumberOfPoints() == 3 and particles.GetNumberOfVerts() == 3, "three bead vertices")
    check(all(abs(r - RADIUS) < 1e-15 for r in p["radius"]), "radius array")
    check(p["grain"] == [-1, -1, -1] and [len(v) for v in p["velocity"]] == [3, 3, 3], "grain and velocity arrays")
    fall = DROP_FROM - 0.5 * G * time * time
    for i in (0, 1):
        print(f"t = {time:.4f} s: bead {i} {points[i][2] - fall:+.2e} m from free fall")
        check(abs(points[i][2] - fall) < 1e-7,  # 7.9e-9 m measured (double, dt 0.16 us)
               f"t = {time}: bead {i} at z = {points[i][2]}, free fall {fall}")
    walls, wall_points, w, _ = read(folder, files["walls"])
    check(walls.GetNumberOfPolys() == 1 and all(abs(q[2]) < 1e-15 for q in wall_points), "the floor quad at z = 0")
    contacts, _, c, _ = read(folder, files["contacts"])
    lines = contacts.GetNumberOfLines()
    if time == 0:  # placed touching, not yet pressing
        return
    check(lines == 1 and c["wall"] == [0], f"t = {time}: one contact, bead 2 on the floor ({lines})")
    if lines == 1:
        weight = DENSITY * 4 / 3 * math.pi * RADIUS**3 * G
        fn = c["normal_force"][0]
        print(f"t = {time:.4f} s: floor contact {fn:.4e} N, weight {weight:.4e} N")
        check(abs(fn - weight) < 0.05 * weight,  # 0.4 % measured at 2 ms, then 1e-4 %
               f"t = {time}: the resting bead's contact {fn} N, weight {weight} N")
        check(abs(w["force"][0][2] + fn) < 1e-9 * weight, "the floor bears the contact's force")


def main():
    simsols, scene, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    base = scene.read_text().replace("position = [0, 0, 0.005]", f"position = [0, 0, {DROP_FROM}]")
    base = base.replace("position = [0.003, 0, 0.005]", f"position = [0.003, 0, {DROP_FROM}]")
    (work / "scene.toml").write_text(scene_text(base))
    whole, split = work / "whole", work / "split"
    run(simsols, [str(work / "scene.toml"), "-o", str(whole)])
    entries = series(whole, "particles")
    steps = [int(f.split("_")[1].split(".")[0]) for _, f in entries]
    dt = entries[-1][0] / steps[-1]
    print(f"{len(entries)} dumps, dt = {dt:.6g} s, last at t = {entries[-1][0]} s")
    # every 2 ms from t = 0, and the end when it is not on that cadence
    check(len(entries) in (6, 7) and entries[-1][0] >= 0.01, f"6 dumps in 0.01 s every {DUMP} s and the end, found {len(entries)}")
    check(all(abs(t - s * dt) <= 1e-12 * t for (t, _), s in zip(entries, steps)), "each time is its step x dt")
    check(all(b - a > 0.9 * DUMP for (a, _), (b, _) in zip(entries, entries[1:6])), "dumps every 2 ms")
    for kind in ("walls", "contacts"):
        check([t for t, _ in series(whole, kind)] == [t for t, _ in entries], f"{kind}.pvd has the same times")
    for (time, _), step in zip(entries, steps):
        names = {k: f"{k}_{step:09d}.vtp" for k in ("particles", "walls", "contacts")}
        check_dump(whole, time, names)
    run(simsols, [str(work / "scene.toml"), "-o", str(split), "--stop-after", str(steps[2] + steps[1] // 2)])
    run(simsols, ["--resume", "-o", str(split)])
    check(series(split, "particles") == entries, "the resumed run's series is the whole run's")
    if FAILURES:
        print(f"{len(FAILURES)} checks failed")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
