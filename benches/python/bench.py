"""Side-by-side timings of the Python package against scipy (docs/performance.md, issue 25).

    python benches/python/bench.py [--repeat 5]

Each case runs both sides alternately in this one process, `--repeat` times, and prints the
medians and their ratio. Needs numpy, scipy and the installed `inbetween` package. Runs
without `OPENBLAS_CORETYPE`/`OPENBLAS_L2_SIZE` (peer.py) and prints the versions and BLAS.
"""

import argparse
import statistics
import time

from peer import describe, normal_speed

normal_speed()  # before numpy is imported (peer.py says why)

import numpy as np
from scipy.spatial.transform import Rotation, RotationSpline

import inbetween


def timed(f):
    start = time.perf_counter()
    f()
    return time.perf_counter() - start


def side_by_side(name, ours, theirs, repeat):
    a, b = [], []
    for _ in range(repeat):
        a.append(timed(ours))
        b.append(timed(theirs))
    ma, mb = statistics.median(a), statistics.median(b)
    print(f"{name}: inbetween {ma:.4f} s, scipy {mb:.4f} s, ratio {mb / ma:.1f}x "
          f"(medians of {repeat})")


def curve_case():
    """Case 1's input: 1001 keys (times, scalar-first quaternions) and 10^6 sorted times."""
    rng = np.random.default_rng(1)
    times = np.cumsum(rng.uniform(0.02, 0.05, 1001))
    q = Rotation.random(1001, random_state=2).as_quat(scalar_first=True)
    t = np.linspace(times[0], times[-1], 1_000_000)
    return times, q, t


def resample_case(frames=7200):
    """Case 2's input: 60 joints x `frames` frames at 120 fps, (frames, 60, 4) scalar first."""
    tt = np.arange(frames)[:, None] / 120.0
    j = np.arange(60)[None, :]
    rv = np.stack([0.6 * np.sin(1.3 * tt + 0.1 * j), 0.4 * np.cos(0.7 * tt - 0.2 * j),
                   0.3 * np.sin(2.1 * tt + 0.05 * j)], axis=-1)
    return Rotation.from_rotvec(rv.reshape(-1, 3)).as_quat(scalar_first=True).reshape(frames, 60, 4)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=5)
    repeat = ap.parse_args().repeat
    print(describe())

    # 1. A curve through 1001 keys, built and evaluated at 10^6 sorted times.
    times, q, t = curve_case()
    side_by_side(
        "Curve(1001 keys)(1e6 sorted times), build + evaluate",
        lambda: inbetween.Curve(times, q)(t),
        lambda: RotationSpline(times, Rotation.from_quat(q, scalar_first=True))(t).as_quat(),
        repeat,
    )

    # 2. 60 joints x 7200 frames resampled 120 -> 100 fps (scipy: one spline per joint).
    frames = 7200
    clip = resample_case(frames)
    grid = inbetween.frame_times(frames, 120, 100)
    key_t = np.arange(frames) / 120.0

    def scipy_resample():
        for joint in range(60):
            RotationSpline(key_t, Rotation.from_quat(clip[:, joint], scalar_first=True))(grid).as_quat()

    side_by_side(
        "resample(60 joints x 7200 frames, 120 -> 100 fps)",
        lambda: inbetween.resample(clip, 120, 100),
        scipy_resample,
        repeat,
    )


if __name__ == "__main__":
    main()
