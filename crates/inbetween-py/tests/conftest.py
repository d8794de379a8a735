"""Shared helpers: the CLI binary the tests compare with, rotation distances, and frames as
CSV for the command line."""

import csv
import os
import pathlib
import shutil

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
