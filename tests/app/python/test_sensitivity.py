"""The sensitivity study from Python and from the command line
(app/experiment/shear_box/sensitivity.h), on its ci preset: a small poured box and
0.2 mm of shear, so it checks that the study runs and reports, not the
paper's figures (docs/sensitivity.md has those).

- simsols.study_sensitivity runs every test and returns the effects; they
  are the differences and elementary effects of the tests it returns;
- the command line, pointed at the same folder, finds every test finished
  (it plans the same tests) and writes the same effects.csv;
- μ_s and μ_r leave the pour alone (the packing is the density factor's),
  and every consolidated specimen has a sphere packing's void ratio.
"""
import csv
import math
import os
import subprocess

import simsols

EXE = os.environ.get("SIMSOLS_EXE", "simsols")


def by_test(result):
    return {t["test"]: t for t in result["tests"]}


def test_sensitivity_study_from_python_and_the_command_line(tmp_path):
    out = str(tmp_path / "sens")
    r = simsols.study_sensitivity(out, preset="ci")
    tests = by_test(r)
    factors = ["mu_s", "mu_r", "restitution", "young_modulus", "preparation_friction"]
    responses = ["peak_angle_deg", "residual_angle_deg", "max_dilatancy_deg"]
    assert set(r["effects"]) == set(factors)
    assert len(r["tests"]) == 18
    base = tests["base"]
    # OAT: the end's response minus the base's
    for f in factors:
        for end in ("low", "high"):
            name = "oat_%s_%s" % (f, end)
            for resp in responses:
                e = r["effects"][f][resp]["oat_" + end]
                if name not in tests:  # E's high end is the paper's value: no test
                    assert math.isnan(e)
                    continue
                assert abs(e - (tests[name][resp] - base[resp])) < 1e-9
                assert tests[name]["factors"][f] != base["factors"][f]
    # Morris: one elementary effect per trajectory and factor, from the tests
    traj = [t for t in r["tests"] if t["design"] == "morris"]
    assert len(traj) == r["trajectories"] * (len(factors) + 1)
    for f in factors:
        for resp in responses:
            e = r["effects"][f][resp]
            assert e["effects"] == r["trajectories"]
            assert e["mu_star"] >= abs(e["mu"]) - 1e-12
    pairs = list(zip(traj, traj[1:]))
    moved = [(a, b) for a, b in pairs if sum(a["factors"][f] != b["factors"][f] for f in factors) == 1]
    assert len(moved) == len(factors) * r["trajectories"]
    # the seeds' spread
    seeds = [base["peak_angle_deg"], tests["noise_seed2"]["peak_angle_deg"]]
    sd = abs(seeds[0] - seeds[1]) / math.sqrt(2)
    assert abs(r["noise_sd"]["peak_angle_deg"] - sd) < 1e-9
    # the pour settles with the preparation friction and the paper's mu_r
    # whatever the test's mu_s and mu_r: the same packing as the base's
    for name in ("oat_mu_s_low", "oat_mu_s_high", "oat_mu_r_low", "oat_mu_r_high"):
        assert tests[name]["void_ratio"] == base["void_ratio"], name
    # every consolidated specimen is a packing of spheres (e from the
    # platen's height and the beads' volume)
    for t in r["tests"]:
        assert t["particles"] > 0 and math.isfinite(t["peak_angle_deg"])
        assert 0.5 < t["shear_void_ratio"] < 1.5, t

    with open(os.path.join(out, "effects.csv")) as f:
        written = f.read()
    run = subprocess.run([EXE, "study", "sensitivity", "--preset", "ci", "--out", out],
                         capture_output=True, text=True, check=True)
    assert run.stderr.count("finished earlier, kept") == 18, run.stderr[-2000:]
    with open(os.path.join(out, "effects.csv")) as f:
        assert f.read() == written
    rows = list(csv.DictReader(open(os.path.join(out, "effects.csv"))))
    mu_s = [x for x in rows if x["factor"] == "mu_s" and x["response"] == "peak_angle_deg"][0]
    assert abs(float(mu_s["morris_mu_star_deg"]) - r["effects"]["mu_s"]["peak_angle_deg"]["mu_star"]) < 1e-4
    for png in ("oat_peak_angle_deg.png", "morris_residual_angle_deg.png", "scale_effect.png"):
        assert os.path.getsize(os.path.join(out, png)) > 10000
