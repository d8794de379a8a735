"""`inbetween.resample` and `frame_times`: exact rates, frame counts, and the CLI's frames."""

import csv
import subprocess
from fractions import Fraction

import numpy as np
import pytest

import inbetween
from conftest import angle, frames_csv


def motion(frames, joints, fps):
    """A smooth motion of `joints` joints sampled at `fps`: (frames, joints, 4), scalar first."""
    t = np.arange(frames)[:, None] / fps
    j = np.arange(joints)[None, :]
    a = 0.8 * np.sin(1.7 * t + 0.3 * j)
    b = 0.5 * np.cos(2.3 * t - 0.2 * j)
    # R_z(a)·R_x(b)
    w = np.cos(a / 2) * np.cos(b / 2)
    x = np.cos(a / 2) * np.sin(b / 2)
    y = np.sin(a / 2) * np.sin(b / 2)
    z = np.sin(a / 2) * np.cos(b / 2)
    return np.stack([w, x, y, z], axis=-1)


def test_frame_counts_and_times_are_exact():
    # 60 s at 120 fps onto 100 fps: 6001 frames, k/100 each.
    t = inbetween.frame_times(7201, 120, 100)
    assert len(t) == 6001
    assert np.array_equal(t, np.arange(6001) / 100)
    # NTSC: "30000/1001", 29.97 and Fraction(30000, 1001) are one rate.
    for rate in ["30000/1001", 29.97, Fraction(30000, 1001)]:
        assert np.array_equal(inbetween.frame_times(31, rate, 24), np.arange(25) / 24)
    # 299/24 s at 30000/1001: frames 0..373 (373.4 fits).
    assert np.array_equal(inbetween.frame_times(300, 24, "30000/1001"),
                          np.arange(374) * 1001 / 30000)
    # A rate taken as given: 59.9999885559082 is not 60 (HumanML3D#176). 600 frames span
    # 599/59.9999885559082 = 9.98333... s: at 20 fps, frames 0..199 (not 0..199.67 rounded up).
    t = inbetween.frame_times(600, 59.9999885559082, 20)
    assert len(t) == int(599 / 59.9999885559082 * 20) + 1 == 200
    assert len(inbetween.frame_times(601, 59.9999885559082, 20)) == 201  # 10.0000019 s
    assert len(inbetween.frame_times(601, 60, 20)) == 201


def test_resample_shapes_and_keys():
    q = motion(121, 5, 120)
    out = inbetween.resample(q, 120, 100)
    assert out.shape == (101, 5, 4) and out.flags["C_CONTIGUOUS"]
    # Every fifth output frame (k/100 = 6k/120 for k a multiple of 5... ) is an input frame:
    # frame 5m at 100 fps is frame 6m at 120 fps.
    assert np.max(angle(out[::5], q[::6])) < 1e-12
    one = inbetween.resample(q[:, 2], 120, 100)
    assert np.array_equal(one, out[:, 2])
    rot, w = inbetween.resample(q, 120, 100, velocity=True)
    assert np.array_equal(rot, out) and w.shape == (101, 5, 3)


def test_resample_agrees_with_interp(cli, tmp_path):
    # Three joints at 120 fps written as a CSV of frame numbers, interp at 100 fps.
    q = motion(241, 3, 120)
    src = frames_csv(tmp_path / "frames.csv", q)
    for scheme, tangent in [("bezier", None), ("bezier", "nam-kim"), ("squad", None), ("slerp", None)]:
        out = tmp_path / f"{scheme}.csv"
        flag = [] if tangent is None else ["--tangent", tangent]
        subprocess.run(
            [cli, "interp", str(src), "--key-fps", "120", "--fps", "100", "--scheme", scheme,
             "--velocity", "--angles", "rad", "-o", str(out), *flag],
            check=True,
        )
        with open(out, newline="") as f:
            rows = list(csv.DictReader(f))
        want = np.array([[float(r[c]) for c in "wxyz"] for r in rows]).reshape(3, -1, 4)
        want_w = np.array([[float(r[c]) for c in ("wx", "wy", "wz")] for r in rows]).reshape(3, -1, 3)
        got, got_w = inbetween.resample(q, 120, 100, scheme=scheme, velocity=True, tangent=tangent)
        assert got.shape == (201, 3, 4)
        assert np.max(angle(got.transpose(1, 0, 2), want)) < 1e-12, scheme
        scale = np.maximum(np.linalg.norm(want_w, axis=-1), 1e-300)
        rel = np.linalg.norm(got_w.transpose(1, 0, 2) - want_w, axis=-1) / scale
        assert np.max(rel) < 1e-9, scheme


@pytest.mark.parametrize(
    "call, says",
    [
        (lambda: inbetween.resample(np.zeros((10, 3)), 30, 24), "rotations: expected shape"),
        (lambda: inbetween.resample(motion(10, 1, 30)[:, 0], 0, 24), "fps_in: expected a positive frame rate"),
        (lambda: inbetween.resample(motion(10, 1, 30)[:, 0], 30, "fast"), "fps_out: expected a positive frame rate"),
        (lambda: inbetween.resample(motion(10, 1, 30)[:, 0], 30, True), "fps_out: expected a frame rate, found a bool"),
        (lambda: inbetween.frame_times(0, 30, 24), "n: expected at least one frame"),
    ],
)
def test_errors_name_the_argument(call, says):
    with pytest.raises(inbetween.InputError) as e:
        call()
    assert says in str(e.value)


def test_rows_are_checked_in_joint_order_with_one_warning():
    # 20 000 frames of 4 joints: the rows are scanned in memory order in chunks of 65 536, and
    # the first row in joint order (then frame order) is the one named, whichever chunk holds it.
    q = motion(20000, 4, 120).copy()
    q[10, 3] *= 1.5      # chunk 0, joint 3
    q[19000, 0] *= 1.02  # chunk 1, joint 0: the first in joint order
    q[19500, 2] *= 1.01
    with pytest.warns(UserWarning) as told:
        inbetween.resample(q, 120, 30)
    assert len(told) == 1
    message = str(told[0].message)
    assert message.startswith("rotations[19000, 0]: quaternion norm 1.02"), message
    assert message.endswith("(and 2 other rows)"), message
    q[12, 3] = 0.0
    q[19999, 1] = 0.0
    with pytest.raises(inbetween.InputError,
                       match=r"rotations\[19999, 1\]: expected a quaternion of non-zero length"):
        inbetween.resample(q, 120, 30)
