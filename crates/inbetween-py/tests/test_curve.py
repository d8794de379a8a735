"""`inbetween.Curve` against scipy and the command line, its shapes, its errors and the GIL."""

import csv
import subprocess
import threading
import time

import numpy as np
import pytest
from scipy.spatial.transform import Rotation, Slerp

import inbetween
from conftest import FIXTURES, angle

SCHEMES = ["hermite", "squad", "bezier", "slerp", "nlerp", "minaccel"]


def keys(k=12, joints=None, seed=7):
    """K random key rotations (scalar first) at strictly increasing, uneven times."""
    rng = np.random.default_rng(seed)
    times = np.cumsum(rng.uniform(0.05, 0.4, k))
    shape = (k, 4) if joints is None else (k, joints, 4)
    q = rng.normal(size=shape)
    return times - times[0], q / np.linalg.norm(q, axis=-1, keepdims=True)


def test_slerp_is_scipy_slerp():
    times, q = keys(30)
    t = np.linspace(times[0], times[-1], 2001)
    got = inbetween.Curve(times, q, "slerp")(t)
    want = Slerp(times, Rotation.from_quat(q, scalar_first=True))(t).as_quat(scalar_first=True)
    assert got.shape == (2001, 4)
    assert np.max(angle(got, want)) < 1e-12


def numpy_nlerp(times, q, t):
    """nlerp from its definition: each key in the hemisphere of the one before, the four
    components lerped between the keys around each time, normalised."""
    q = q.copy()
    for i in range(1, len(q)):
        if np.dot(q[i], q[i - 1]) < 0:
            q[i] = -q[i]
    i = np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(times) - 2)
    u = np.clip((t - times[i]) / (times[i + 1] - times[i]), 0.0, 1.0)[:, None]
    p = (1 - u) * q[i] + u * q[i + 1]
    return p / np.linalg.norm(p, axis=-1, keepdims=True)


def test_nlerp_is_numpy_nlerp():
    times, q = keys(30)
    t = np.linspace(times[0], times[-1], 2001)
    c = inbetween.Curve(times, q, scheme="nlerp")
    assert c.scheme == "nlerp"
    got = c(t)
    assert np.max(angle(got, numpy_nlerp(times, q, t))) < 1e-12
    # Its velocity (world frame, ω = 2·q'·q⁻¹) against differences of numpy's nlerp inside
    # the segments.
    mid = 0.5 * (times[:-1] + times[1:])
    h = 1e-6
    dq = (numpy_nlerp(times, q, mid + h) - numpy_nlerp(times, q, mid - h)) / (2 * h)
    r = numpy_nlerp(times, q, mid)
    w = 2 * (r[:, :1] * dq[:, 1:] - dq[:, :1] * r[:, 1:] + np.cross(r[:, 1:], dq[:, 1:]))
    got = c(mid, 1)
    assert np.max(np.linalg.norm(got - w, axis=-1) / np.linalg.norm(w, axis=-1)) < 1e-6


def test_nlerp_reduce_plays_back_under_numpy_nlerp():
    from test_resample import motion

    q = motion(241, 2, 60)
    r = inbetween.reduce(q, 60, 0.5, scheme="nlerp")
    t = inbetween.frame_times(241, 60, 60)
    for j in range(2):
        k = r.keys[j]
        err = np.degrees(angle(numpy_nlerp(t[k], q[k, j], t), q[:, j]))
        assert err.max() <= 0.5 + 1e-9, (j, err.max())


@pytest.mark.parametrize("scheme", SCHEMES)
def test_every_scheme_passes_through_its_keys(scheme):
    times, q = keys(9, joints=3)
    c = inbetween.Curve(times, q, scheme, grid_rate=240)
    got = c(times)
    assert got.shape == (9, 3, 4)
    assert np.max(angle(got, q)) < 1e-9
    assert np.allclose(np.linalg.norm(got, axis=-1), 1.0, atol=1e-14)


def test_joints_are_the_curves_of_each_joint_alone():
    times, q = keys(10, joints=4)
    t = np.linspace(-0.1, times[-1] + 0.1, 333)
    together = inbetween.Curve(times, q, "squad", ends="rest")
    for j in range(4):
        alone = inbetween.Curve(times, q[:, j], "squad", ends="rest")
        for order in (0, 1, 2):
            assert np.array_equal(together(t, order, outside="hold")[:, j],
                                  alone(t, order, outside="hold"))


def test_outside_the_span_is_refused_unless_held():
    times, q = keys(5)
    c = inbetween.Curve(times, q)
    lo, hi = c.span
    # Within 1e-9 s of an end is the end (the frame clock's tolerance).
    assert np.array_equal(c(hi + 5e-10), c(hi))
    with pytest.raises(inbetween.InputError, match=r"t\[1\]: .* outside the keys' span"):
        c([lo, hi + 1e-6])
    with pytest.raises(inbetween.InputError, match="outside the keys' span"):
        c(lo - 0.5, order=1)
    # Held: the end keys at rest (zero rates), as before.
    assert np.array_equal(c(hi + 1.0, outside="hold"), c(hi))
    assert np.array_equal(c(lo - 1.0, order=1, outside="hold"), np.zeros(3))
    with pytest.raises(inbetween.InputError, match="outside: expected"):
        c(lo, outside="clamp")


def test_shapes_orders_and_conventions():
    times, q = keys(6)
    c = inbetween.Curve(times, q)
    assert c(0.3).shape == (4,)
    assert c([0.1, 0.2]).shape == (2, 4)
    assert c(np.array([0.1, 0.2]), order=1).shape == (2, 3)
    assert c(np.array([0.1, 0.2]), order=2).shape == (2, 3)
    out = c(np.linspace(0, 1, 5))
    assert out.flags["C_CONTIGUOUS"] and out.dtype == np.float64
    assert c.joints is None and c.scheme == "bezier" and c.span == (times[0], times[-1])
    # Scalar last in and out: the same curve, the components moved.
    last = inbetween.Curve(times, q[:, [1, 2, 3, 0]], scalar_first=False)
    t = np.linspace(0, times[-1], 50)
    assert np.array_equal(last(t), c(t)[:, [1, 2, 3, 0]])
    # A scipy Rotation is its quaternions, and gives a Rotation back (tests/test_frames.py).
    rot = inbetween.Curve(times, Rotation.from_quat(q, scalar_first=True))
    assert np.max(angle(rot(t).as_quat(scalar_first=True), c(t))) < 1e-15


def test_angular_velocity_of_a_constant_spin():
    # 90°/s about z, keyed every 0.25 s: every scheme's velocity is (0, 0, π/2) inside.
    times = np.arange(9) * 0.25
    a = np.pi / 2 * times
    q = np.stack([np.cos(a / 2), 0 * a, 0 * a, np.sin(a / 2)], axis=1)
    t = np.linspace(0.01, 1.99, 97)
    for scheme in ["hermite", "squad", "bezier", "slerp"]:
        w = inbetween.Curve(times, q, scheme)(t, order=1)
        assert np.allclose(w, [0, 0, np.pi / 2], atol=1e-9), scheme
        assert np.allclose(inbetween.Curve(times, q, scheme)(t, order=2), 0, atol=1e-7), scheme


def read_frames(path):
    """time, quaternion, angular velocity (rad/s) of interp's CSV output (--angles rad)."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    t = np.array([float(r["time"]) for r in rows])
    q = np.array([[float(r[c]) for c in "wxyz"] for r in rows])
    w = np.array([[float(r[c]) for c in ("wx", "wy", "wz")] for r in rows])
    return t, q, w


@pytest.mark.parametrize("scheme", SCHEMES)
def test_agrees_with_interp(cli, tmp_path, scheme):
    # fixtures/interp/nonuniform.csv: 5 keys at uneven times; interp at 30 fps.
    src = FIXTURES / "interp" / "nonuniform.csv"
    with open(src, newline="") as f:
        rows = list(csv.DictReader(f))
    times = np.array([float(r["time"]) for r in rows])
    q = np.array([[float(r[c]) for c in "wxyz"] for r in rows])
    out = tmp_path / "frames.csv"
    subprocess.run(
        [cli, "interp", str(src), "--fps", "30", "--scheme", scheme, "--velocity",
         "--angles", "rad", "-o", str(out)],
        check=True,
    )
    t, want_q, want_w = read_frames(out)
    c = inbetween.Curve(times, q, scheme, grid_rate=30)
    assert np.max(angle(c(t), want_q)) < 1e-12
    got_w = c(t, order=1)
    scale = np.maximum(np.linalg.norm(want_w, axis=1), 1e-300)
    # interp's velocity at a key is the segment's leaving it, as Curve's.
    assert np.max(np.linalg.norm(got_w - want_w, axis=1) / scale) < 1e-9


@pytest.mark.parametrize("scheme, tangent", [("bezier", "nam-kim"), ("hermite", "spline"), ("bezier", None)])
def test_tangent_rule_agrees_with_interp(cli, tmp_path, scheme, tangent):
    # 12 keys at uneven times (the spline tangent's window is seven keys): Curve(tangent=...)
    # and resample(tangent=...) are interp --tangent's curves; the two rules differ.
    times, q = keys(12, seed=3)
    src = tmp_path / "keys.csv"
    with open(src, "w", newline="") as f:
        f.write("time,w,x,y,z\n")
        for t, r in zip(times, q):
            f.write(",".join(repr(float(x)) for x in [t, *r]) + "\n")
    out = tmp_path / "frames.csv"
    flag = [] if tangent is None else ["--tangent", tangent]
    subprocess.run(
        [cli, "interp", str(src), "--fps", "30", "--scheme", scheme, "--velocity",
         "--angles", "rad", "-o", str(out), *flag],
        check=True,
    )
    t, want_q, _ = read_frames(out)
    c = inbetween.Curve(times, q, scheme, tangent=tangent)
    assert np.max(angle(c(t), want_q)) < 1e-12
    other = {"spline": "nam-kim", "nam-kim": "spline", None: "nam-kim"}[tangent]
    assert np.max(angle(inbetween.Curve(times, q, scheme, tangent=other)(t), want_q)) > 1e-4
    with pytest.raises(inbetween.InputError, match="tangent: expected a tangent rule"):
        inbetween.Curve(times, q, scheme, tangent="catmull")


def test_velocities_tcb_and_end_velocities():
    times, q = keys(5)
    v = np.full((5, 3), np.nan)
    v[2] = [0.5, -1.0, 2.0]
    c = inbetween.Curve(times, q, "bezier", velocities=v)
    assert np.allclose(c(times[2], order=1), v[2], atol=1e-12)
    start = inbetween.Curve(times, q, "hermite", start_velocity=[0, 0, 1.5])
    assert np.allclose(start(times[0], order=1), [0, 0, 1.5], atol=1e-12)
    tense = inbetween.Curve(times, q, "bezier", tcb=np.tile([1.0, 0.0, 0.0], (5, 1)))
    # Tension 1 stops at every key.
    assert np.allclose(tense(times[1:-1], order=1), 0, atol=1e-12)


@pytest.mark.parametrize(
    "call, says",
    [
        (lambda: inbetween.Curve([0, 1], np.zeros((2, 3))), "rotations: expected shape (K, 4) or (K, J, 4)"),
        (lambda: inbetween.Curve([0, 1, 2], [[1, 0, 0, 0]] * 2), "times: 3 times for 2 rotations"),
        (lambda: inbetween.Curve([0, 0], [[1, 0, 0, 0]] * 2), "rotations"),
        (lambda: inbetween.Curve([0, 1], [[1, 0, 0, 0]] * 2, "cubic"), "scheme: expected a scheme"),
        (lambda: inbetween.Curve([0, 1], [[1, 0, 0, 0]] * 2, ends="loose"), "ends: expected chord"),
        (lambda: inbetween.Curve([0, 1], [[1, 0, 0, 0]] * 2)(0.5, order=3), "order: expected 0"),
        (lambda: inbetween.Curve([0, 1], [[1, 0, 0, 0]] * 2)(np.nan), "t: expected finite times"),
        (lambda: inbetween.Curve([0, 1], [["a", 0, 0, 0]] * 2), "rotations: expected an array of numbers"),
        (lambda: inbetween.Curve([0, 1], [[1, 0, 0, 0]] * 2, velocities=np.zeros((3, 3))), "velocities: shape"),
    ],
)
def test_errors_name_the_argument(call, says):
    with pytest.raises(inbetween.InputError) as e:
        call()
    assert says in str(e.value)
    assert isinstance(e.value, ValueError)
    assert "--" not in str(e.value), "no command-line flag in a library message"


def test_evaluation_releases_the_gil():
    # While one thread evaluates a large curve, this thread runs Python. Were the GIL held by
    # the call, this thread could run only for a switch interval (5 ms) or two at the call's
    # start and end, and not in between (measured with `sorted` of 3·10⁷ ints, which holds it:
    # ticks over 8 ms of a 0.78 s call): here no gap between its ticks is half the call.
    times, q = keys(1001, seed=3)
    c = inbetween.Curve(times, q)
    t = np.linspace(times[0], times[-1], 1_000_000)
    span = []

    def work():
        start = time.perf_counter()
        c(t, order=1)
        span.extend([start, time.perf_counter()])

    worker = threading.Thread(target=work)
    stamps = []
    worker.start()
    while worker.is_alive():
        stamps.append(time.perf_counter())
    worker.join()
    start, end = span
    assert end - start > 0.3, f"the call took {end - start:.3f} s: too short to tell"
    ticks = [start] + [s for s in stamps if start < s < end] + [end]
    gap = max(b - a for a, b in zip(ticks, ticks[1:]))
    assert gap < 0.5 * (end - start), (gap, end - start)


def test_nlerp_resample_is_numpy_nlerp():
    from test_resample import motion

    q = motion(61, 1, 30)[:, 0]
    got = inbetween.resample(q, 30, 48, scheme="nlerp")
    t_in = inbetween.frame_times(61, 30, 30)
    t_out = inbetween.frame_times(61, 30, 48)
    assert got.shape == (len(t_out), 4)
    assert np.max(angle(got, numpy_nlerp(t_in, q, t_out))) < 1e-12
