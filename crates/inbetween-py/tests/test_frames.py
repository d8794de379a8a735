"""Rates in the world and the body frame (`frame=`), scipy `Rotation` in and out, `__version__`.

Finite differences of the rotations are the reference for both frames: the world-frame rate is
the rotation vector of R(t + h) R(t − h)ᵀ over 2h, the body-frame rate that of
R(t − h)ᵀ R(t + h) over 2h (both O(h²) from the rate). scipy's `RotationSpline(t, 1)` is shown
to be a body-frame rate by the same two formulas on its own rotations, and to equal
`frame="body"` on a curve both libraries draw alike (a spin at a constant rate)."""

import importlib.metadata
import pathlib
import re
import tomllib

import numpy as np
import pytest
from scipy.spatial.transform import Rotation, RotationSpline, Slerp

import inbetween
from conftest import FIXTURES, ROOT

SCHEMES = ["hermite", "squad", "bezier", "slerp", "minaccel"]
H = 1e-6  # rotation differences: truncation ~h²·|d³R/dt³|, rounding ~1e-16/h
H2 = 1e-6  # rate differences (order 2)


def keys(k=12, joints=None, seed=7):
    """K random key rotations (scalar first) at strictly increasing, uneven times."""
    rng = np.random.default_rng(seed)
    times = np.cumsum(rng.uniform(0.05, 0.4, k))
    shape = (k, 4) if joints is None else (k, joints, 4)
    q = rng.normal(size=shape)
    return times - times[0], q / np.linalg.norm(q, axis=-1, keepdims=True)


def rot(q):
    return Rotation.from_quat(q, scalar_first=True)


def fd_rates(r_minus, r_plus, h):
    """World and body rates by central differences of two scipy Rotations at t ∓ h."""
    world = (r_plus * r_minus.inv()).as_rotvec() / (2 * h)
    body = (r_minus.inv() * r_plus).as_rotvec() / (2 * h)
    return world, body


def away_from(t, knots, h):
    """The times of t at least 10·h from every knot (a key, a grid point): a central difference
    straddles no joint of two pieces."""
    d = np.min(np.abs(t[:, None] - np.asarray(knots)[None, :]), axis=1)
    return t[d > 10 * h]


def relative(got, want, scale=None):
    """The largest difference of rows relative to the reference's size (rows near zero measured
    against a hundredth of the largest row, or of ``scale`` where the reference is zero: a
    slerp's acceleration, against its rates)."""
    n = np.linalg.norm(want, axis=-1)
    floor = 1e-2 * max(n.max(), 1e-300 if scale is None else scale)
    return float(np.max(np.linalg.norm(got - want, axis=-1) / np.maximum(n, floor)))


def sample_times(times, n, seed=3):
    """n random times inside the keys' span, away from the keys."""
    rng = np.random.default_rng(seed)
    t = np.sort(rng.uniform(times[0] + 1e-3, times[-1] - 1e-3, n))
    return away_from(t, times, H)


def flat(a):
    return a.reshape(-1, a.shape[-1])


def check_against_differences(curve, t):
    """Largest relative differences of (world ω, body ω, world α, body α) with differences."""
    if curve.scheme == "minaccel":
        # minaccel joins its solved grid points (keys and points between) by great arcs, at a
        # constant rate each: the times whose ±h straddle a grid point are those where the rate
        # changes between t − h and t + h (in any joint); every other time is inside an arc.
        jump = np.linalg.norm(curve(t + H, 1) - curve(t - H, 1), axis=-1)
        jump = jump.reshape(len(t), -1).max(axis=1)
        inside = jump <= 1e-9 * np.linalg.norm(flat(curve(t, 1)), axis=-1).max()
        assert inside.mean() > 0.9
        t = t[inside]
    q_minus, q_plus = flat(curve(t - H)), flat(curve(t + H))
    fd_world, fd_body = fd_rates(rot(q_minus), rot(q_plus), H)
    w_world, w_body = flat(curve(t, 1)), flat(curve(t, 1, frame="body"))
    # The derivation, by differences alone: d/dt of the body rate R(t)ᵀ ω(t) (differences of
    # frame="body") equals R(t)ᵀ dω/dt (differences of the world rate, turned by Rᵀ).
    dw_world = (flat(curve(t + H2, 1)) - flat(curve(t - H2, 1))) / (2 * H2)
    dw_body = (flat(curve(t + H2, 1, frame="body"))
               - flat(curve(t - H2, 1, frame="body"))) / (2 * H2)
    rt = rot(flat(curve(t))).inv()
    # A slerp's rates are constant (zero derivative): measured against its rates' size, per s.
    rate = np.linalg.norm(w_world, axis=-1).max()
    errors = {
        "world ω": relative(w_world, fd_world),
        "body ω": relative(w_body, fd_body),
        "d/dt Rᵀω = Rᵀ dω/dt": relative(dw_body, rt.apply(dw_world), rate),
    }
    # The library's own accelerations against those differences: a 4-point numerical
    # derivative of ω for the segment schemes (docs/spec.md §4.5), so within 1e-4, not 1e-6;
    # minaccel's is the slope of its grid's rates, not the (zero) derivative along an arc.
    if curve.scheme != "minaccel":
        errors["world α ~"] = relative(flat(curve(t, 2)), dw_world, rate)
        errors["body α ~"] = relative(flat(curve(t, 2, frame="body")), dw_body, rate)
    return errors


def assert_within(errors):
    exact = {k: v for k, v in errors.items() if not k.endswith("~")}
    assert max(exact.values()) < 1e-6, errors
    assert max(errors.values()) < 1e-4, errors


@pytest.mark.parametrize("scheme", SCHEMES)
def test_both_frames_are_finite_differences_random(scheme):
    times, q = keys(12, joints=3)
    curve = inbetween.Curve(times, q, scheme, grid_rate=30)
    t = sample_times(times, 300)
    errors = check_against_differences(curve, t)
    print(scheme, {k: f"{v:.2e}" for k, v in errors.items()})
    assert_within(errors)


@pytest.mark.parametrize("scheme", SCHEMES)
def test_both_frames_are_finite_differences_real(scheme):
    # fixtures/bvh/cmu_01_01.bvh: 31 joints of motion capture at 120 fps, every frame a key;
    # keys every 8th frame, as a reduced clip keeps them.
    clip = inbetween.read(FIXTURES / "bvh" / "cmu_01_01.bvh")
    times, q = clip.times[::8], clip.rotations[::8]
    curve = inbetween.Curve(times, q, scheme, grid_rate=30)
    t = sample_times(times, 200)
    errors = check_against_differences(curve, t)
    print(scheme, {k: f"{v:.2e}" for k, v in errors.items()})
    assert_within(errors)
    # The frames differ on real data: the body rate is not the world rate.
    w, b = curve(t, 1), curve(t, 1, frame="body")
    assert np.max(np.linalg.norm(w - b, axis=-1)) > 0.1


@pytest.mark.parametrize("data", ["random", "real"])
def test_body_frame_is_the_inverse_rotation_of_the_world_frame(data):
    if data == "random":
        times, q = keys(15, joints=4, seed=11)
    else:
        clip = inbetween.read(FIXTURES / "bvh" / "cmu_01_01.bvh")
        times, q = clip.times[::4], clip.rotations[::4]
    t = np.linspace(times[0], times[-1], 777)
    for scheme in SCHEMES:
        curve = inbetween.Curve(times, q, scheme)
        r = rot(curve(t).reshape(-1, 4))
        for order in (1, 2):
            world = curve(t, order).reshape(-1, 3)
            body = curve(t, order, frame="body").reshape(-1, 3)
            want = r.inv().apply(world)
            scale = np.max(np.linalg.norm(want, axis=-1))
            assert np.max(np.linalg.norm(body - want, axis=-1)) <= 1e-12 * scale, (scheme, order)
            # The default is the world frame, as before.
            assert np.array_equal(curve(t, order, frame="world"), curve(t, order))


def test_scipy_rotation_spline_rate_is_body_frame():
    # scipy's convention, from scipy alone: RotationSpline(t, 1) is the body-frame difference
    # quotient of its own rotations, not the world-frame one; RotationSpline(t, 2) the time
    # derivative of that body-frame rate. Random keys, and every joint of cmu_01_01.bvh keyed
    # every 8th frame (LeftArm: world and body rates up to 3.9 rad/s apart).
    clip = inbetween.read(FIXTURES / "bvh" / "cmu_01_01.bvh")
    cases = [("random",) + keys(12, seed=5)]
    cases += [(name, clip.times[::8], clip.rotations[::8, j]) for j, name in enumerate(clip.names)]
    for name, times, q in cases:
        spline = RotationSpline(times, rot(q))
        t = away_from(np.linspace(times[0] + 1e-3, times[-1] - 1e-3, 400), times, H)
        fd_world, fd_body = fd_rates(spline(t - H), spline(t + H), H)
        rate = spline(t, 1)
        scale = np.linalg.norm(rate, axis=-1).max()
        if scale == 0:
            continue  # a joint that does not turn
        assert relative(rate, fd_body) < 1e-6, name
        if name in ("random", "LeftArm"):
            assert relative(rate, fd_world) > 0.5, name
        da = (spline(t + H2, 1) - spline(t - H2, 1)) / (2 * H2)
        assert relative(spline(t, 2), da, scale) < 1e-6, name


def test_body_frame_equals_rotation_spline_where_the_curves_coincide():
    # A spin at a constant body rate ω_b from a random start R0: R(t) = R0 exp(t ω_b). scipy's
    # RotationSpline through its keys (at uneven times) is that curve, and so is every scheme's
    # curve here (a geodesic at constant speed): RotationSpline(t, 1) = ω_b = frame="body",
    # where the world frame gives R0 ω_b.
    rng = np.random.default_rng(21)
    for trial in range(5):
        r0 = Rotation.random(random_state=rng.integers(1 << 31))
        wb = rng.normal(size=3) * 2
        times = np.cumsum(rng.uniform(0.05, 0.2, 10))
        times -= times[0]
        key_rot = r0 * Rotation.from_rotvec(times[:, None] * wb)
        spline = RotationSpline(times, key_rot)
        t = np.linspace(times[0], times[-1], 501)
        want = spline(t, 1)
        assert relative(want, np.tile(wb, (len(t), 1))) < 1e-9
        for scheme in ["slerp", "hermite", "squad", "bezier"]:
            curve = inbetween.Curve(times, key_rot, scheme)
            assert relative(curve(t, 1, frame="body"), want) < 1e-9, scheme
            assert relative(curve(t, 1), r0.apply(want)) < 1e-9, scheme
            assert relative(curve(t, 1), want) > 1e-3  # the world frame is another vector


def test_frame_keyword_is_checked():
    times, q = keys(5)
    curve = inbetween.Curve(times, q)
    with pytest.raises(inbetween.InputError, match=r"^frame: expected \"world\" or \"body\""):
        curve([0.1], 1, frame="local")
    with pytest.raises(TypeError, match="frame"):
        curve([0.1], 1, frame=1)
    with pytest.raises(inbetween.InputError, match=r"^frame: "):
        inbetween.resample(q, 10, 20, velocity=True, frame="Body")
    # The raw extension checks it too.
    with pytest.raises(inbetween.InputError, match=r"^frame: "):
        inbetween._ext.Curve(times, q)(np.array([0.1]), 1, "inertial")
    # Rotations (order 0) are the same in either frame.
    assert np.array_equal(curve([0.1, 0.2], frame="body"), curve([0.1, 0.2]))


def test_resample_body_frame():
    clip = inbetween.read(FIXTURES / "bvh" / "cmu_01_01.bvh")
    frames, world = inbetween.resample(clip.rotations, 120, 50, velocity=True)
    frames_b, body = inbetween.resample(clip.rotations, 120, 50, velocity=True, frame="body")
    assert np.array_equal(frames, frames_b)
    want = rot(frames.reshape(-1, 4)).inv().apply(world.reshape(-1, 3)).reshape(body.shape)
    assert np.max(np.linalg.norm(body - want, axis=-1)) <= 1e-12 * np.max(np.linalg.norm(want, axis=-1))
    # As Curve gives them at the same times.
    t = inbetween.frame_times(len(clip.times), 120, 50)
    curve = inbetween.Curve(clip.times, clip.rotations)
    assert np.allclose(body, curve(t, 1, frame="body"), rtol=0, atol=1e-9)


def test_rotation_in_rotation_out():
    times, q = keys(10, seed=13)
    r = rot(q)
    t = np.linspace(times[0], times[-1], 301)
    arrays = inbetween.Curve(times, q)(t)  # w first
    got = inbetween.Curve(times, r)(t)
    assert isinstance(got, Rotation) and len(got) == len(t)
    want = Rotation.from_quat(arrays, scalar_first=True)
    assert np.max(np.abs(got.as_quat() - want.as_quat())) <= 1e-12
    # At the keys, the keys (up to sign).
    at_keys = inbetween.Curve(times, r)(times).as_quat()
    sign = np.sign(np.sum(at_keys * r.as_quat(), axis=-1))[:, None]
    assert np.max(np.abs(sign * at_keys - r.as_quat())) <= 1e-12
    # One time: one Rotation; rates stay arrays; scalar_first= asks for arrays.
    c = inbetween.Curve(times, r)
    one = c(0.3)
    assert isinstance(one, Rotation) and one.single
    assert c(t, 1).shape == (len(t), 3)
    assert np.max(np.abs(c(t, scalar_first=True) - arrays)) <= 1e-12
    assert np.max(np.abs(c(t, scalar_first=False) - arrays[:, [1, 2, 3, 0]])) <= 1e-12
    # Arrays in: arrays out in their own order, unless asked.
    last = inbetween.Curve(times, q[:, [1, 2, 3, 0]], scalar_first=False)
    assert np.array_equal(last(t), arrays[:, [1, 2, 3, 0]])
    assert np.array_equal(last(t, scalar_first=True), arrays)
    assert np.array_equal(inbetween.Curve(times, q)(t, scalar_first=True), arrays)
    # Several joints: a Rotation of shape (N, J) where scipy has them.
    rj = rot(keys(10, joints=3, seed=2)[1])
    if len(getattr(rj, "shape", ())) == 2:
        got = inbetween.Curve(times, rj)(t)
        assert isinstance(got, Rotation) and got.shape == (len(t), 3)
    # resample: a Rotation of frames gives a Rotation of frames.
    frames = inbetween.resample(q, 10, 25)
    out = inbetween.resample(r, 10, 25)
    assert isinstance(out, Rotation)
    assert np.max(np.abs(out.as_quat() - Rotation.from_quat(frames, scalar_first=True).as_quat())) <= 1e-12
    out, w = inbetween.resample(r, 10, 25, velocity=True)
    assert isinstance(out, Rotation) and w.shape == (len(frames), 3)


def test_scipy_slerp_reads_the_rotation_back():
    # The trap of issue 47: w-first arrays read by Rotation.from_quat (x first) are other
    # rotations; a Rotation in gives a Rotation out, nothing to misread.
    times, q = keys(8, seed=4)
    t = np.linspace(times[0], times[-1], 101)
    got = inbetween.Curve(times, rot(q), "slerp")(t)
    want = Slerp(times, rot(q))(t)
    assert np.max((got.inv() * want).magnitude()) < 1e-12


def test_version():
    py = tomllib.loads((ROOT / "crates" / "inbetween-py" / "pyproject.toml").read_text())
    cargo = tomllib.loads((ROOT / "Cargo.toml").read_text())
    assert inbetween.__version__ == py["project"]["version"]
    assert inbetween.__version__ == cargo["workspace"]["package"]["version"]
    assert re.fullmatch(r"\d+\.\d+\.\d+.*", inbetween.__version__)
    assert "__version__" in inbetween.__all__
    # The version is the installed distribution's, which is `inbetween-rs` (the PyPI name
    # `inbetween` is another project's), and the extension was built from the same version.
    assert py["project"]["name"] == inbetween._DISTRIBUTION == "inbetween-rs"
    assert importlib.metadata.version("inbetween-rs") == inbetween.__version__
    assert inbetween._inbetween.__version__ == inbetween.__version__
    assert "inbetween-rs" in importlib.metadata.packages_distributions()["inbetween"]
    # The licence the wheel declares (PEP 639), and its texts installed beside it.
    meta = importlib.metadata.metadata("inbetween-rs")
    assert meta["License-Expression"] == "MIT OR Apache-2.0"
    licence_files = sorted(meta.get_all("License-File"))
    assert licence_files == ["LICENSE-APACHE", "LICENSE-MIT", "THIRD-PARTY-LICENSES"], licence_files
    installed = {pathlib.PurePath(str(f)).name: f for f in importlib.metadata.files("inbetween-rs")}
    assert "ufbx" in installed["THIRD-PARTY-LICENSES"].read_text()
    assert installed["LICENSE-MIT"].read_text() == (ROOT / "LICENSE-MIT").read_text()
