"""Fitting from Python: the example data recover the rate they were made with, as the command
line does."""
import csv
import os
import subprocess

import numpy as np
import pytest

import whirl


def _points(repo):
    with open(os.path.join(repo, "data", "fit_example.csv")) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return (np.array([float(r["r"]) for r in rows]), np.array([float(r["z"]) for r in rows]))


def test_fit_example_recovers_the_rate_and_agrees_with_the_cli(repo, whirl_program):
    r, z = _points(repo)
    f = whirl.fit(r, z, length=120, gravity=981)  # cm and cm/s^2, as in the file
    true = 3.2 * np.sqrt(981 / 120)  # the rate the data were made with (file header)
    assert f.mode == 2 and f.mirrored
    assert abs(f.omega - true) < 3 * f.omega_err
    assert f.rms_residual == pytest.approx(0.12, rel=0.3)  # the noise put in: 0.12 cm
    out = subprocess.run([whirl_program, "fit", "--shape", os.path.join(repo, "data",
                          "fit_example.csv"), "--length", "120", "--gravity", "981"],
                         capture_output=True, text=True, check=True).stdout
    cli = out.strip().split("\n")[-1].split(",")
    assert f.omega == pytest.approx(float(cli[0]), rel=1e-12)
    assert f.omega_err == pytest.approx(float(cli[1]), rel=1e-9)


def test_fit_of_an_exact_shape():
    s = whirl.shape(2.385, 1, points=41)
    f = whirl.fit(s.r[1:], s.z[1:], mode=1)
    assert f.omega == pytest.approx(2.385, rel=1e-8)
