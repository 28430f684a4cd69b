"""splinelab resample (the command line) against the Python package's
zoom, shift, rotate and affine_transform on the same data (the engine's
modes: mirror, reflect, grid-wrap), .npy in and out; bad input exits 2
and writes nothing."""

import os
import pathlib
import subprocess

import numpy as np
import pytest

import splinelab

ROOT = pathlib.Path(__file__).resolve().parents[2]
EPS = np.finfo(np.float64).eps


def cli():
    exe = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release" / "splinelab"
    if not exe.exists():
        pytest.skip(f"{exe} not built")
    return exe


def resample(tmp_path, x, *args):
    src, dst = tmp_path / "x.npy", tmp_path / "y.npy"
    np.save(src, x)
    r = subprocess.run([str(cli()), "resample", "--input", str(src), "--output", str(dst), *args],
                       capture_output=True, text=True)
    return r, (np.load(dst) if r.returncode == 0 else None), dst


@pytest.mark.parametrize("mode", ["mirror", "reflect", "grid-wrap"])
def test_cli_equals_python(tmp_path, mode):
    x = np.random.default_rng(40).uniform(-1, 1, (30, 34))
    m = np.array([[0.9, 0.2, 1.5], [-0.3, 1.1, -4.0]])
    np.save(tmp_path / "m.npy", m)
    cases = [
        (["--zoom", "1.7,0.8"], splinelab.zoom(x, (1.7, 0.8), order=5, mode=mode)),
        (["--zoom", "1.3", "--grid-mode"], splinelab.zoom(x, 1.3, order=5, mode=mode, grid_mode=True)),
        (["--shift", "2.5,-3.25"], splinelab.shift(x, (2.5, -3.25), order=5, mode=mode)),
        (["--rotate", "30"], splinelab.rotate(x, 30, order=5, mode=mode)),
        (["--matrix", str(tmp_path / "m.npy"), "--output-shape", "25,40"],
         splinelab.affine_transform(x, m, output_shape=(25, 40), order=5, mode=mode)),
    ]
    for args, ref in cases:
        r, y, _ = resample(tmp_path, x, "--degree", "5", "--mode", mode, *args)
        assert r.returncode == 0, r.stderr
        assert y.shape == ref.shape, args
        assert np.abs(y - ref).max() <= 16 * EPS * np.abs(ref).max(), args


def test_cli_float32_stays_float32(tmp_path):
    x = np.random.default_rng(41).uniform(-1, 1, (20, 22)).astype(np.float32)
    r, y, _ = resample(tmp_path, x, "--degree", "3", "--zoom", "2")
    assert r.returncode == 0 and y.dtype == np.float32
    ref = splinelab.zoom(x, 2, order=3, mode="mirror")
    assert np.abs(y - ref).max() <= 16 * np.finfo(np.float32).eps * np.abs(ref).max()


def test_cli_bad_input_exits_2_and_writes_nothing(tmp_path):
    x = np.ones((5, 6))
    for args in (["--zoom", "1,2,3"], ["--rotate", "10", "--zoom", "2"], ["--shift", "nan"]):
        r, _, dst = resample(tmp_path, x, "--degree", "3", *args)
        assert r.returncode == 2, (args, r.stderr)
        assert not dst.exists()
    r, _, dst = resample(tmp_path, np.ones(5), "--degree", "3", "--rotate", "10")
    assert r.returncode == 2 and "2-D" in r.stderr and not dst.exists()
