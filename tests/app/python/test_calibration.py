"""The calibration's prediction from Python (app/experiment/calibration/prediction.h):
a calibrated friction, written as `simsols calibrate` writes it, predicts the
small periodic-cell triaxial test on two new specimens; the band's mean lies
between its least and largest specimen, the measured curve (the program's
own run of the same material on seed 1) sits inside the band, and the
command line, pointed at the same folder, keeps every test and writes the
same table. The fit itself is checked by tests/app/experiment/calibration.
"""
import csv
import math
import os
import subprocess

import simsols

EXE = os.environ.get("SIMSOLS_EXE", "simsols")
ASSETS = os.path.join(os.path.dirname(__file__), "..", "..", "..", "assets")
SCENE = os.path.abspath(os.path.join(ASSETS, "tests", "periodic_triaxial_small.toml"))


def test_prediction_from_python_and_the_command_line(tmp_path):
    measured = tmp_path / "measured"
    simsols.run_test(simsols.load_scene(SCENE), str(measured))
    (tmp_path / "calibrated.toml").write_text(
        '[calibrated]\n"materials.beads.sliding_friction" = 0.3\n')
    (tmp_path / "pred.toml").write_text(
        '[prediction]\ncalibrated = "calibrated.toml"\nspecimens = 2\npoints = 10\nat = [0.05]\n'
        '[[tests]]\nname = "p100"\nscene = "%s"\ndata = "measured/cell.csv"\nwhere = "stage=1"\n'
        'x = { column = "strain", unit = "-", quantity = "axial_strain" }\n'
        '[[tests.y]]\ncolumn = "stress_ratio"\nunit = "-"\nquantity = "stress_ratio"\n' % SCENE)
    out = str(tmp_path / "out")
    r = simsols.predict(str(tmp_path / "pred.toml"), out)
    band = r["p100"]["stress_ratio"]
    assert len(band["x"]) == 10 and len(band["peak"]) == 2
    for mean, sd in zip(band["mean"], band["sd"]):
        assert math.isfinite(mean) and sd >= 0
    # the same material on two other specimens (seeds 2001, 2002):
    # most of the measured curve lies inside their prediction interval
    assert band["inside"] >= 0.5, band
    assert band["rms_error"] < 0.2
    table = open(os.path.join(out, "prediction.csv")).read()
    cli = subprocess.run([EXE, "predict", str(tmp_path / "pred.toml"), "--out", out, "-q"],
                         capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    assert open(os.path.join(out, "prediction.csv")).read() == table
    rows = list(csv.DictReader(open(os.path.join(out, "specimens.csv"))))
    assert [r["specimen"] for r in rows] == ["1", "2"]
