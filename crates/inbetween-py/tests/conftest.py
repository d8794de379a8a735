"""Shared helpers: the CLI binary the tests compare with, the Khronos glTF Validator and the
independent glTF playback reference (fixtures/gltf/playback_ref.py) the glTF output is checked
with, rotation distances, and frames as CSV for the command line.

Each of those tools skips its tests when it is missing, unless INBETWEEN_REQUIRE_CLI is set
(CI, .ci/run): then a missing one is a failure (the validator also with
INBETWEEN_REQUIRE_GLTF_VALIDATOR, the reference with INBETWEEN_REQUIRE_PYTHON_CHECKS, as for
cargo test)."""

import csv
import json
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]
FIXTURES = ROOT / "fixtures"


def _cli():
    """The `inbetween` binary: $INBETWEEN_BIN, else the workspace's debug or release build."""
    given = os.environ.get("INBETWEEN_BIN")
    if given:
        return given
    for build in ("debug", "release"):
        path = ROOT / "target" / build / "inbetween"
        if path.is_file():
            return str(path)
    return shutil.which("inbetween")


@pytest.fixture(scope="session")
def cli():
    path = _cli()
    if path is None:
        if os.environ.get("INBETWEEN_REQUIRE_CLI"):
            pytest.fail("no inbetween binary (INBETWEEN_BIN, target/debug or target/release)")
        pytest.skip("no inbetween binary to compare with")
    return path


def _missing(what, also):
    if os.environ.get("INBETWEEN_REQUIRE_CLI") or os.environ.get(also):
        pytest.fail(f"{what} is required but missing")
    pytest.skip(f"{what} is missing")


@pytest.fixture(scope="session")
def gltf_validator():
    """``validate(path)``: runs ``node tools/gltf-validator/validate.js path``, asserts the
    Khronos glTF Validator reports no error, and returns its report."""
    tool = ROOT / "tools" / "gltf-validator"
    if shutil.which("node") is None or not (tool / "node_modules" / "gltf-validator").is_dir():
        _missing("the glTF Validator (node and `npm ci --prefix tools/gltf-validator`)",
                 "INBETWEEN_REQUIRE_GLTF_VALIDATOR")

    def validate(path):
        o = subprocess.run(["node", str(tool / "validate.js"), str(path)], capture_output=True,
                           text=True)
        assert o.returncode == 0, f"{path}: the glTF Validator reports errors:\n{o.stderr}\n{o.stdout}"
        return json.loads(o.stdout)

    return validate


@pytest.fixture(scope="session")
def playback():
    """``play(asset, animation, channel, times)``: fixtures/gltf/playback_ref.py's JSON, the
    channel played as glTF 2.0 Appendix C defines it, by pygltflib and numpy (run with the
    checkers' interpreter, target/ci-venv, as the Rust tests run it)."""
    python = ROOT / "target" / "ci-venv" / "bin" / "python"
    if not python.exists():
        _missing("target/ci-venv (the checkers' Python, with pygltflib)",
                 "INBETWEEN_REQUIRE_PYTHON_CHECKS")

    def play(asset, animation, channel, times):
        args = [str(python), str(FIXTURES / "gltf" / "playback_ref.py"), str(asset),
                str(animation), str(channel), *(repr(float(t)) for t in times)]
        o = subprocess.run(args, capture_output=True, text=True, cwd=ROOT)
        assert o.returncode == 0, o.stderr
        return json.loads(o.stdout)

    return play


def angle(a, b):
    """Geodesic angle (rad) between unit quaternions in rows of a and b (either sign)."""
    d = np.abs(np.sum(np.asarray(a) * np.asarray(b), axis=-1))
    n = np.linalg.norm(np.asarray(a) - np.sign(np.sum(a * b, axis=-1))[..., None] * b, axis=-1)
    # 4·asin(|a − b|/2) is accurate near zero, where 2·acos(|a·b|) is not.
    return np.where(d > 0.9, 4.0 * np.arcsin(np.minimum(n / 2.0, 1.0)), 2.0 * np.arccos(np.minimum(d, 1.0)))


def frames_csv(path, q):
    """Frames q (T, J, 4) written as a CSV of frame numbers, tracks j0, j1, …; returns path."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["track", "frame", "w", "x", "y", "z"])
        for j in range(q.shape[1]):
            for k in range(q.shape[0]):
                w.writerow([f"j{j}", k, *(repr(float(x)) for x in q[k, j])])
    return path
