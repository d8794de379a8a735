"""AMASS .npz files through Python: read, resample, and written back in AMASS's layout at an
exact rate, checked with numpy and scipy alone (np.load, Rotation.from_rotvec, Slerp, exact
fractions of the frame clock), never with inbetween's own reader."""

from fractions import Fraction

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as R
from scipy.spatial.transform import Slerp

import inbetween
from conftest import FIXTURES


def smplh(path, frames, fps, compressed, seed=7):
    """An AMASS-shaped SMPL-H file of slow smooth motion (as fixtures/amass/generate.py)."""
    rng = np.random.default_rng(seed)
    t = np.arange(frames)[:, None] / fps
    amp, freq = rng.uniform(0.1, 0.5, 156), rng.uniform(0.1, 0.4, 156)
    phase = rng.uniform(0, 2 * np.pi, 156)
    arrays = {
        "trans": np.hstack([0.8 * t, 0.1 * np.sin(t), 0.9 + 0 * t]),
        "gender": np.array("female"),
        "mocap_framerate": np.array(fps),
        "betas": rng.normal(size=16),
        "dmpls": rng.normal(size=(frames, 8)),
        "poses": amp * np.sin(2 * np.pi * freq * t + phase),
    }
    (np.savez_compressed if compressed else np.savez)(path, **arrays)
    return arrays


def angles(a, b):
    """Angle (rad) between the rotations of rotation-vector rows a and b, per joint."""
    ra, rb = R.from_rotvec(a.reshape(-1, 3)), R.from_rotvec(b.reshape(-1, 3))
    return (ra.inv() * rb).magnitude()


@pytest.mark.parametrize("compressed", [False, True])
def test_5994_to_30_is_on_the_exact_clock_and_loads_as_amass(tmp_path, compressed):
    src = smplh(tmp_path / "in.npz", 3001, 59.94, compressed)
    inbetween.resample_amass(tmp_path / "in.npz", tmp_path / "out.npz", 30)
    out = np.load(tmp_path / "out.npz")
    rate_in = Fraction(60000, 1001)
    last = Fraction(3000) / rate_in
    m = int(last * 30) + 1
    assert m == 1502
    assert list(out.keys()) == list(src)
    for k, v in src.items():
        shape = (m,) + v.shape[1:] if k in ("poses", "trans", "dmpls") else v.shape
        assert (out[k].dtype, out[k].shape) == (v.dtype, shape), k
    assert out["mocap_framerate"] == 30.0 and out["gender"] == "female"
    assert np.array_equal(out["betas"], src["betas"])
    # Shared frames: 0 s and 1001/30 s (source frame 2000: k/30 = i·1001/60000).
    assert angles(out["poses"][0], src["poses"][0]).max() < 1e-12
    assert angles(out["poses"][1001], src["poses"][2000]).max() < 1e-12
    # Every frame k at k/30 s exactly: position i + u among the source frames, as a fraction.
    pos = [Fraction(k, 30) * rate_in for k in range(m)]
    i = np.array([int(p) for p in pos])
    u = np.array([float(p - int(p)) for p in pos])
    nxt = np.minimum(i + 1, 3000)
    want = src["trans"][i] * (1 - u)[:, None] + src["trans"][nxt] * u[:, None]
    assert np.abs(out["trans"] - want).max() < 1e-12
    # Rotations: within a curve's departure from slerp of the two frames around k/30 s ...
    slerp_err = []
    stride_err = []
    for j in range(52):
        rots = R.from_rotvec(src["poses"][:, 3 * j:3 * j + 3])
        ref = Slerp(np.arange(3001), rots)(i + u)
        got = R.from_rotvec(out["poses"][:, 3 * j:3 * j + 3])
        slerp_err.append((ref.inv() * got).magnitude().max())
        stride = rots[::2]  # one frame short of the clock's m, as well as late
        stride_err.append((ref[: len(stride)].inv() * stride).magnitude().max())
    # ... while poses[::2] puts frame 2k (at 2k·1001/60000 s) at k/30 s: 50 ms late by 50 s.
    assert max(slerp_err) < 2e-4, max(slerp_err)
    assert max(stride_err) > 100 * max(slerp_err), (max(stride_err), max(slerp_err))


def test_120_to_30_keeps_every_fourth_frame(tmp_path):
    src = np.load(FIXTURES / "amass" / "smplh_120.npz")
    inbetween.resample_amass(FIXTURES / "amass" / "smplh_120.npz", tmp_path / "o.npz", 30)
    out = np.load(tmp_path / "o.npz")
    assert out["poses"].shape == (16, 156) and out["mocap_framerate"].dtype == np.float64
    assert angles(out["poses"], src["poses"][::4]).max() < 1e-12
    assert np.array_equal(out["trans"], src["trans"][::4])
    assert np.array_equal(out["dmpls"], src["dmpls"][::4])


def test_read_gives_the_joints_and_resample_puts_them_on_the_grid():
    clip = inbetween.read(FIXTURES / "amass" / "smplx_60.npz")
    assert (clip.format, clip.fps, len(clip.names)) == ("npz", "60", 55)
    assert clip.names[:3] == ["pelvis", "left_hip", "right_hip"] and clip.names[22] == "jaw"
    assert list(clip.parents[:4]) == [-1, 0, 0, 0] and clip.parents[22] == 15
    src = np.load(FIXTURES / "amass" / "smplx_60.npz")
    q = clip.rotations  # (31, 55, 4), w first
    rv = R.from_quat(q.reshape(-1, 4), scalar_first=True).as_rotvec().reshape(31, 165)
    assert angles(rv, src["poses"]).max() < 1e-12
    assert np.array_equal(clip.translations[:, 0], src["trans"])
    frames = inbetween.resample(q, clip.fps, 30)
    assert frames.shape == (16, 55, 4)
    got = R.from_quat(frames.reshape(-1, 4), scalar_first=True).as_rotvec().reshape(16, 165)
    assert angles(got, src["poses"][::2]).max() < 1e-12


@pytest.mark.parametrize("name,want", [
    ("bad_truncated.npz", "not a readable zip archive (.npz)"),
    ("bad_no_poses.npz", "no key \"poses\""),
    ("bad_shape.npz", "key \"poses\": expected float rotation vectors"),
    ("bad_object.npz", "key \"gender\": an object array"),
])
def test_malformed_files_raise_input_error_naming_file_and_key(tmp_path, name, want):
    with pytest.raises(inbetween.InputError, match=name) as e:
        inbetween.read(FIXTURES / "amass" / name)
    assert want in str(e.value)
    with pytest.raises(inbetween.InputError, match=want.replace("(", r"\(").replace(")", r"\)")):
        inbetween.resample_amass(FIXTURES / "amass" / name, tmp_path / "o.npz", 30)
