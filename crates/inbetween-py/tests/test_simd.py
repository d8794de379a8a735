"""The AVX2 build of the extension (``_inbetween_avx2``, tools/wheel/build.sh) against the
portable one: the same code compiled for wider lanes without FMA, so every result must be the
same bits. A build from the source folder has no AVX2 module: the test then skips, unless
``INBETWEEN_REQUIRE_AVX2=1`` (the wheel's tests in CI) says it must be there."""

import os

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import inbetween
from inbetween import _inbetween as portable

try:
    from inbetween import _inbetween_avx2 as avx2
except ImportError:
    avx2 = None

required = os.environ.get("INBETWEEN_REQUIRE_AVX2") == "1"
if avx2 is None or not portable.cpu_has_avx2():
    if required:
        raise RuntimeError("INBETWEEN_REQUIRE_AVX2=1 but the wheel has no _inbetween_avx2 module "
                           "or this CPU lacks AVX2")
    pytestmark = pytest.mark.skip(reason="no _inbetween_avx2 module here, or no AVX2 on this CPU")


def same_bits(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and np.array_equal(a.view(np.uint8), b.view(np.uint8))


def keys(n, seed):
    rng = np.random.default_rng(seed)
    times = np.cumsum(rng.uniform(0.02, 0.05, n))
    q = Rotation.random(n, random_state=seed).as_quat(scalar_first=True)
    return times, q


def test_the_package_uses_the_avx2_module():
    if os.environ.get("INBETWEEN_SIMD", "").strip().lower() == "portable":
        assert inbetween._ext is portable
    else:
        assert inbetween._ext is avx2


@pytest.mark.parametrize("scheme", ["bezier", "squad", "hermite", "slerp", "nlerp", "minaccel"])
def test_curves_are_the_same_bits(scheme):
    times, q = keys(301, 4)
    t = np.linspace(times[0], times[-1], 40_001)
    a, b = portable.Curve(times, q, scheme), avx2.Curve(times, q, scheme)
    for order in (0, 1, 2):
        for frame in ("world", "body"):
            assert same_bits(a(t, order, frame), b(t, order, frame)), (scheme, order, frame)


def test_a_curve_that_could_differ_does():
    # The comparison is not vacuous: a different curve gives other bits.
    times, q = keys(301, 4)
    t = np.linspace(times[0], times[-1], 1001)
    assert not same_bits(portable.Curve(times, q, "bezier")(t), avx2.Curve(times, q, "squad")(t))


@pytest.mark.parametrize("fps_out", [100, 30, 240, "30000/1001", 7])
def test_resample_is_the_same_bits(fps_out):
    frames = 600
    tt = np.arange(frames)[:, None] / 120.0
    j = np.arange(12)[None, :]
    rv = np.stack([0.6 * np.sin(1.3 * tt + 0.1 * j), 0.4 * np.cos(7.7 * tt - 0.2 * j),
                   0.3 * np.sin(2.1 * tt + 0.05 * j)], axis=-1)
    clip = Rotation.from_rotvec(rv.reshape(-1, 3)).as_quat(scalar_first=True).reshape(frames, 12, 4)
    for scheme in ["bezier", "squad", "hermite", "slerp"]:
        x = portable.resample(clip, 120, fps_out, scheme=scheme, velocity=True)
        y = avx2.resample(clip, 120, fps_out, scheme=scheme, velocity=True)
        for u, v in zip(x if isinstance(x, tuple) else (x,), y if isinstance(y, tuple) else (y,)):
            assert same_bits(u, v), (fps_out, scheme)
