"""`import simsols` (app/python/module.cpp), run by ctest under pytest.

- the Hertz impact of tests/solver/kernels/test_hertz.cpp, through the module;
- a scene edited as a dict equals the same edit made to the TOML file, bit
  for bit, and both run to the same state;
- bad dicts fail as bad files do, naming the field and the allowed range;
- arrays and a checkpoint's round trip.
"""
import math
import os
import re

import numpy as np
import pytest

import simsols

ASSETS = os.environ.get("SIMSOLS_ASSETS_DIR", os.path.join(os.path.dirname(__file__), "../../../assets"))


def hertz_theory(mstar, rstar, estar, v):
    """Johnson, Contact Mechanics, sec. 11.4: peak overlap, peak force, duration."""
    k = 4.0 / 3.0 * estar * math.sqrt(rstar)
    d = (15.0 * mstar * v * v / (16.0 * estar * math.sqrt(rstar))) ** 0.4
    c = math.sqrt(math.pi) * math.gamma(1.4) / math.gamma(0.9)
    return d, k * d**1.5, 2.0 * c * d / v


def test_hertz_impact_through_the_module():
    E, nu, rho, R, v = 48e9, 0.2, 2800.0, 0.01, 20.0
    m = rho * 4.0 / 3.0 * math.pi * R**3
    estar = E / (2.0 * (1.0 - nu * nu))
    overlap, force, duration = hertz_theory(m / 2, R / 2, estar, v)
    scene = simsols.scene_from_dict(
        {
            "scene": {"name": "hertz"},
            "materials": [{"name": "glass48", "young_modulus": E, "poisson_ratio": nu,
                           "density": rho, "restitution": 1.0}],
            "particles": [
                {"material": "glass48", "radius": R, "position": [-R - 1e-5, 0.0, 0.0], "velocity": [v / 2, 0.0, 0.0]},
                {"material": "glass48", "radius": R, "position": [R + 1e-5, 0.0, 0.0], "velocity": [-v / 2, 0.0, 0.0]},
            ],
            "effects": {"gravity": [0.0, 0.0, 0.0]},
            "numerics": {"precision": "double", "dt": duration / 487.3, "duration": 1.0},
        },
        name="hertz")
    sim = simsols.Simulation(scene)
    peak_overlap = peak_force = touching = 0.0
    touched = False
    for _ in range(200000):
        sim.advance(1)
        x, f = sim.positions(), sim.forces()
        if sim.contact_counts()[0] > 0:
            touched = True
            touching += sim.dt
        elif touched:
            break
        peak_force = max(peak_force, float(np.linalg.norm(f[0])))
        peak_overlap = max(peak_overlap, 2 * R - abs(x[1, 0] - x[0, 0]))
    print(f"[measure] overlap {peak_overlap:.6e} vs {overlap:.6e}, force {peak_force:.6e} vs {force:.6e}, "
          f"duration {touching:.6e} vs {duration:.6e}")
    # the C++ test's tolerances: about ten times the errors achieved
    assert peak_overlap / overlap == pytest.approx(1.0, abs=1e-4)
    assert peak_force / force == pytest.approx(1.0, abs=1e-4)
    assert touching / duration == pytest.approx(1.0, abs=0.006)
    u = sim.velocities()
    assert (u[1, 0] - u[0, 0]) / v == pytest.approx(1.0, abs=0.01)  # elastic: they part at 20 m/s


def shear_box_text():
    with open(os.path.join(ASSETS, "scenes", "shear_box.toml"), encoding="utf-8") as f:
        return f.read()


def test_a_scene_edited_as_a_dict_equals_the_same_edit_of_the_file():
    text = shear_box_text()
    d = simsols.load_scene(os.path.join(ASSETS, "scenes", "shear_box.toml")).to_dict()
    old = d["shear_box"]["normal_stress"]
    d["shear_box"]["normal_stress"] = 2 * old
    from_dict = simsols.scene_from_dict(d, name="edited")
    edited, n = re.subn(r"(?m)^normal_stress\s*=\s*[^#\n]*", f"normal_stress = {2 * old!r}", text)
    assert n == 1
    from_file = simsols.parse_scene(edited, "edited.toml")
    assert from_dict.to_toml() == from_file.to_toml()
    assert from_dict.to_toml() != simsols.parse_scene(text, "shear_box.toml").to_toml()
    a, b = simsols.Simulation(from_dict), simsols.Simulation(from_file)
    a.advance(200)
    b.advance(200)
    assert a.particles == b.particles > 100
    assert np.array_equal(a.positions(), b.positions())  # bit for bit
    assert np.array_equal(a.velocities(), b.velocities())


def test_bad_values_are_refused_as_in_a_file():
    d = simsols.load_scene(os.path.join(ASSETS, "scenes", "settling_bead.toml")).to_dict()
    d["materials"][0]["poisson_ratio"] = 0.7
    with pytest.raises(simsols.SceneError) as e:
        simsols.scene_from_dict(d, name="bad_bead")
    assert isinstance(e.value, ValueError)
    assert e.value.file == "bad_bead"
    assert "poisson_ratio" in e.value.field
    message = str(e.value)
    assert "bad_bead" in message and "poisson_ratio" in message and "0.5" in message, message
    d["materials"][0]["poisson_ratio"] = np.float32(0.25)  # NumPy numbers are numbers
    assert "0.25" in simsols.scene_from_dict(d).to_toml()
    d["materials"][0]["poisson_ratio"] = 0.2
    d["numerics"]["precison"] = "double"  # a misspelt key
    with pytest.raises(simsols.SceneError, match="precision"):
        simsols.scene_from_dict(d)
    with pytest.raises(TypeError, match="numerics.bad"):
        simsols.scene_from_dict({"numerics": {"bad": object()}})
    with pytest.raises(simsols.SceneError, match="no_such.toml"):
        simsols.load_scene("no_such.toml")


def test_a_scene_read_is_placed_before_it_runs():
    """read_scene only reads; place() and Simulation place what it describes."""
    path = os.path.join(ASSETS, "scenes", "default.toml")
    read = simsols.read_scene(path)
    assert not read.placed and read.particles == 0
    placed = simsols.load_scene(path)
    assert placed.placed and placed.particles > 0
    assert simsols.Simulation(read).particles == placed.particles
    assert not read.placed  # Simulation placed its own copy
    read.place()
    assert read.placed and read.to_toml() == placed.to_toml()


def test_arrays_and_a_checkpoint_round_trip(tmp_path):
    scene = simsols.load_scene(os.path.join(ASSETS, "scenes", "shear_box.toml"))
    sim = simsols.Simulation(scene)
    sim.advance(100)
    x = sim.positions()
    assert x.shape == (sim.particles, 3) and x.dtype == np.float64
    assert sim.radii().shape == (sim.particles,)
    assert np.all(sim.radii() > 0)
    pairs, forces = sim.contacts()
    assert pairs.shape[1] == 2 and forces.shape == (pairs.shape[0], 3)
    path = str(tmp_path / "c.bin")
    sim.save_checkpoint(path)
    back = simsols.load_checkpoint(path)
    assert back.steps == sim.steps == 100
    assert np.array_equal(back.positions(), x)
    sim.advance(50)
    back.advance(50)
    assert np.array_equal(back.positions(), sim.positions())  # continues identically


def test_a_shear_test_from_python_equals_simsols_run(tmp_path):
    """run_test gives the summary and rows `simsols run` writes for the same scene."""
    path = os.path.join(ASSETS, "tests", "shear_small.toml")
    scene = simsols.read_scene(path)  # only read: the run places it, as the command does
    assert not scene.placed and scene.particles == 0
    r = simsols.run_test(scene, str(tmp_path / "py"))
    assert r["apparatus"] == "shear_box" and r["finished"]
    exe = os.environ["SIMSOLS_EXE"]
    cli = tmp_path / "cli"
    assert os.system(f"'{exe}' run '{path}' --out '{cli}' -q > /dev/null") == 0
    with open(cli / "summary.txt", encoding="utf-8") as f:
        keys = dict(line.split(" = ", 1) for line in f.read().splitlines() if " = " in line)
    assert set(keys) == set(r["summary"])
    for key, text in keys.items():
        if key == "wall_seconds":
            continue
        value = r["summary"][key]
        assert (float(text) == value) if isinstance(value, float) else (text == value), key
    table = np.genfromtxt(cli / "shear.csv", delimiter=",", names=True)
    assert len(r["rows"]["displacement_mm"]) == len(table) > 10
    for name in table.dtype.names:
        assert np.array_equal(r["rows"][name], table[name]), name
    # the Python run wrote the same outputs as the command
    assert (tmp_path / "py" / "summary.txt").exists() and (tmp_path / "py" / "shear.csv").exists()
    with pytest.raises(simsols.SceneError, match="no apparatus"):
        simsols.run_test(simsols.load_scene(os.path.join(ASSETS, "scenes", "settling_bead.toml")), str(tmp_path / "x"))


def test_a_test_stopped_at_the_end_of_a_stage_hands_its_apparatus_over(tmp_path):
    """stop_at stops a shear test consolidated, before it shears: its
    checkpoint loads with the apparatus' walls (the platen servo-held on the
    specimen), and the same test resumed by `simsols run --resume` finishes
    with the rows of a run straight through."""
    path = os.path.join(ASSETS, "tests", "shear_small.toml")
    r = simsols.run_test(simsols.load_scene(path), str(tmp_path / "py"), stop_at="consolidate")
    assert not r["finished"] and r["stopped_after"] == "consolidate" and r["stage"] == "shear"
    assert len(r["rows"]["displacement_mm"]) <= 1  # at most the row at rest
    sim = simsols.load_checkpoint(r["checkpoint"])
    assert sim.steps == r["steps"]
    walls = sim.walls()
    box = [w for w in walls if w["apparatus"] == "shear_box"]
    assert len(box) == 12
    platen = [w for w in box if w["servo"]]
    assert len(platen) == 1 and platen[0]["name"] == "platen" and platen[0]["normal"][2] == -1.0
    # its target is the normal stress on the box's area, carried by a dead
    # weight (shear_box.loading's default), and the beads push it up with
    # that load (within the servo's 1 % equilibrium band, shear_programme.h)
    box_table = simsols.load_scene(path).to_dict()["shear_box"]
    load = box_table["normal_stress"] * box_table["length"] * box_table["width"]
    assert platen[0]["servo"]["target_force"] == pytest.approx(load, rel=1e-6)
    assert platen[0]["servo"]["dead_weight_mass"] > 0
    assert platen[0]["force"][2] == pytest.approx(load, rel=0.05)
    with pytest.raises(simsols.SceneError, match="not a stage"):
        simsols.run_test(simsols.load_scene(path), str(tmp_path / "bad"), stop_at="consolidated")
    # stop_at="prepared": the specimen placed and prepared, nothing loaded yet
    p = simsols.run_test(simsols.read_scene(path), str(tmp_path / "prepared"), stop_at="prepared")
    assert not p["finished"] and p["stopped_after"] == "prepared"
    assert p["steps"] == 0 and p["stage"] == "settle"
    assert simsols.load_checkpoint(p["checkpoint"]).particles == simsols.load_scene(path).particles
    exe = os.environ["SIMSOLS_EXE"]
    assert os.system(f"'{exe}' run --resume --out '{tmp_path / 'py'}' -q > /dev/null") == 0
    straight = tmp_path / "straight"
    assert os.system(f"'{exe}' run '{path}' --out '{straight}' -q > /dev/null") == 0
    assert (tmp_path / "py" / "shear.csv").read_text() == (straight / "shear.csv").read_text()


def test_a_periodic_cell_runs_from_python(tmp_path):
    """The periodic cell (docs/periodic-cell.md) through the module: its
    rows as arrays, the servo holding sigma_zz at the pressure while it
    shears (within 1 %, as tests/solver/apparatus/test_periodic_cell.cpp
    measures 0.3 %), and its summary's steady values."""
    path = os.path.join(ASSETS, "tests", "periodic_small.toml")
    r = simsols.run_test(simsols.load_scene(path), str(tmp_path / "cell"))
    assert r["finished"] and r["apparatus"] == "periodic_cell"
    rows = r["rows"]
    shear = np.asarray(rows["stage"]) == 1
    assert shear.sum() >= 20
    assert np.mean(np.asarray(rows["sigma_zz_kPa"])[shear]) == pytest.approx(100, rel=0.01)
    assert float(r["summary"]["stress_ratio"]) > 0.2
    assert float(r["summary"]["solid_fraction"]) == pytest.approx(np.mean(np.asarray(rows["solid_fraction"])[shear & (np.asarray(rows["strain"]) >= 0.15)]), rel=1e-6)
