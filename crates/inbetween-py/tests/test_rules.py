"""The command line's rules, as Python applies them: quaternions normalised as the readers
normalise them, a track of one key, compared with what `inbetween interp` writes for the same
input (docs/spec.md §2, §3)."""

import subprocess
import warnings

import numpy as np
import pytest

import inbetween
from conftest import angle


def cli_frames(cli, tmp_path, rows, fps="30"):
    """`inbetween interp` of a CSV of keys `rows` (time, w, x, y, z), its frames (N, 4)."""
    src = tmp_path / "keys.csv"
    src.write_text("time,w,x,y,z\n" + "".join(",".join(map(str, r)) + "\n" for r in rows))
    out = subprocess.run([cli, "interp", str(src), "--fps", fps], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()[1:]
    return np.array([[float(x) for x in line.split(",")[2:6]] for line in lines]), out.stderr


def test_quaternions_written_to_four_decimals_are_normalised_as_the_cli_does(cli, tmp_path):
    # 0.7071 is 1e-5 off the unit norm: accepted silently by both, normalised.
    rows = [(0.0, 1, 0, 0, 0), (1.0, 0.7071, 0.7071, 0, 0)]
    want, stderr = cli_frames(cli, tmp_path, rows)
    assert "norm" not in stderr
    keys = np.array([r[1:] for r in rows], dtype=float)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        got = inbetween.Curve([0.0, 1.0], keys)(np.arange(31) / 30)
    assert angle(got, want).max() < 1e-9
    assert np.abs(np.linalg.norm(got, axis=1) - 1).max() < 1e-15


def test_a_norm_off_by_more_than_1e3_warns_once_and_is_normalised(cli, tmp_path):
    rows = [(0.0, 1.01, 0, 0, 0), (0.5, 1.02, 0, 0, 0), (1.0, 0, 0, 0, 2)]
    want, stderr = cli_frames(cli, tmp_path, rows)
    assert "off 1 by more than 1e-3; normalized" in stderr
    keys = np.array([r[1:] for r in rows], dtype=float)
    with pytest.warns(UserWarning) as told:
        got = inbetween.Curve([0.0, 0.5, 1.0], keys)(np.arange(31) / 30)
    assert len(told) == 1
    message = str(told[0].message)
    assert message.startswith("rotations[0]: quaternion norm 1.01 is off 1 by more than 1e-3")
    assert message.endswith("(and 2 other rows)"), message
    assert angle(got, want).max() < 1e-9
    # Joints are named too; a zero quaternion is refused, naming its row.
    with pytest.raises(inbetween.InputError, match=r"rotations\[1, 0\]: expected a quaternion of non-zero length"):
        inbetween.Curve([0.0, 1.0], np.array([[[1.0, 0, 0, 0]], [[0.0, 0, 0, 0]]]))


def test_one_frame_is_a_constant_as_on_the_command_line(cli, tmp_path):
    q = np.array([[0.0, 0.6, 0.0, 0.8]])
    want, _ = cli_frames(cli, tmp_path, [(0.0, *q[0])])
    got = inbetween.resample(q, 30, 24)
    assert got.shape == (1, 4) and want.shape == (1, 4)
    assert angle(got, want).max() < 1e-15
    frames, w = inbetween.resample(q[:, None, :], 30, 24, velocity=True)
    assert frames.shape == (1, 1, 4) and np.array_equal(w, np.zeros((1, 1, 3)))
    c = inbetween.Curve([0.25], q)
    assert angle(c(np.array([0.25])), q).max() < 1e-15
    assert np.array_equal(c(np.array([0.25]), order=1), np.zeros((1, 3)))


def test_translations_are_resampled_as_interp_writes_them(cli, tmp_path):
    # Two joints, 9 frames at 24 fps onto 30 fps, each with a moving translation.
    t = np.arange(9) / 24
    q = np.stack([np.stack([np.cos(0.3 * t * (j + 1)), np.sin(0.3 * t * (j + 1)),
                            np.zeros_like(t), np.zeros_like(t)], -1) for j in range(2)], 1)
    p = np.stack([np.stack([np.sin(t + j), t ** 2, np.full_like(t, j)], -1) for j in range(2)], 1)
    src = tmp_path / "moves.csv"
    with open(src, "w") as f:
        f.write("track,frame,w,x,y,z,tx,ty,tz\n")
        for j in range(2):
            for k in range(len(t)):
                f.write(",".join([f"j{j}", str(k), *map(repr, q[k, j].tolist()), *map(repr, p[k, j].tolist())]) + "\n")
    out = subprocess.run([cli, "interp", str(src), "--key-fps", "24", "--fps", "30"],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    header, *lines = out.stdout.splitlines()
    cols = header.split(",")
    rows = [line.split(",") for line in lines]
    want_p = np.array([[float(r[cols.index(c)]) for c in ("tx", "ty", "tz")] for r in rows]).reshape(2, -1, 3)
    want_q = np.array([[float(r[cols.index(c)]) for c in ("w", "x", "y", "z")] for r in rows]).reshape(2, -1, 4)
    got_q, got_p = inbetween.resample(q, 24, 30, translations=p)
    assert got_p.shape == (want_p.shape[1], 2, 3)
    assert np.abs(got_p - want_p.transpose(1, 0, 2)).max() < 1e-12
    assert angle(got_q.reshape(-1, 4), want_q.transpose(1, 0, 2).reshape(-1, 4)).max() < 1e-12
    # With velocities the positions come last; a shape that does not match is refused.
    r, w, pos = inbetween.resample(q, 24, 30, translations=p, velocity=True)
    assert np.array_equal(pos, got_p) and w.shape == (len(pos), 2, 3)
    with pytest.raises(inbetween.InputError, match="translations: shape"):
        inbetween.resample(q, 24, 30, translations=p[:, :1])
    bad = p.copy()
    bad[2, 1, 1] = np.nan
    with pytest.raises(inbetween.InputError, match=r"translations\[2, 1\]: expected a finite number, found NaN"):
        inbetween.resample(q, 24, 30, translations=bad)
    with pytest.raises(inbetween.InputError, match="expected at least 1 key"):
        inbetween.Curve(np.zeros(0), np.zeros((0, 4)))


def test_angles_contradicting_a_documents_own_unit_are_refused(tmp_path):
    doc = tmp_path / "deg.json"
    doc.write_text('{"angles": "deg", "rotation": "euler:ZYX", "keys": '
                   '[{"time": 0, "euler": [0, 0, 90]}, {"time": 1, "euler": [0, 0, 180]}]}')
    # Its own unit, whether or not said: 90° about x.
    for given in (None, "deg"):
        q = inbetween.read(doc, angles=given).tracks[0][1]
        assert angle(q[:1], np.array([[np.cos(np.pi / 4), np.sin(np.pi / 4), 0, 0]])).max() < 1e-12
    with pytest.raises(inbetween.InputError, match='declares "angles": "deg" but angles says rad'):
        inbetween.read(doc, angles="rad")
    # A CSV declares none: angles says what its numbers are.
    csv = tmp_path / "rad.csv"
    csv.write_text("time,e1,e2,e3\n0,0,0,1.5707963267948966\n1,0,0,3.141592653589793\n")
    q = inbetween.read(csv, rotation="euler:ZYX", angles="rad").tracks[0][1]
    assert angle(q[:1], np.array([[np.cos(np.pi / 4), np.sin(np.pi / 4), 0, 0]])).max() < 1e-12
