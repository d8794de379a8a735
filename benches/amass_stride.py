#!/usr/bin/env python3
"""AMASS resampling against the integer-stride loop users write today (docs/performance.md,
*AMASS resampling against a stride*).

For a made-up AMASS SMPL-H file of SECONDS seconds (numpy, as fixtures/amass/generate.py) at
120 fps and at 59.94 fps, both to 30 fps:

- the stride loop: `poses[::4]` (120 → 30) and `poses[::2]` (59.94 → 30, what people write);
  frame k of it is source frame s·k, at s·k/rate_in seconds where the clock says k/30: the
  largest gap (seconds) and the largest rotation error it makes there (degrees, against scipy's
  Slerp of the source at k/30 s, a reference independent of inbetween), and its frame count
  against the clock's ⌊(F−1)/rate_in · 30⌋ + 1;
- inbetween: `inbetween.resample_amass(in, out, 30)` (the whole file: read, curves, write),
  its gap (0 by construction: frame k is at k/30) and the same rotation error (the departure of
  its curve from slerp between samples, not a clock error);
- the time of each, best of REPEAT.

    python3 benches/amass_stride.py [SECONDS] [REPEAT]
"""
import sys
import tempfile
import time
from fractions import Fraction
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation as R
from scipy.spatial.transform import Slerp

import inbetween


def make(path, frames, fps):
    rng = np.random.default_rng(47)
    t = np.arange(frames)[:, None] / fps
    amp, freq = rng.uniform(0.1, 0.5, 156), rng.uniform(0.1, 1.0, 156)
    phase = rng.uniform(0, 2 * np.pi, 156)
    poses = amp * np.sin(2 * np.pi * freq * t + phase)
    np.savez(path, trans=np.hstack([t, 0 * t, 0.9 + 0 * t]), gender=np.array("male"),
             mocap_framerate=np.array(fps), betas=np.zeros(16), dmpls=np.zeros((frames, 8)),
             poses=poses)
    return poses


def worst_degrees(src, rate, times, frames):
    """Largest angle (deg) between `frames` (M, 156) and the source slerped at `times` (s)."""
    pos = np.array([float(t * rate) for t in times])
    worst = 0.0
    for j in range(52):
        ref = Slerp(np.arange(len(src)), R.from_rotvec(src[:, 3 * j:3 * j + 3]))(pos)
        got = R.from_rotvec(frames[:, 3 * j:3 * j + 3])
        worst = max(worst, (ref.inv() * got).magnitude().max())
    return np.degrees(worst)


def best(f, repeat):
    out = None
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t0)
    return min(times), out


def main():
    seconds = float(sys.argv[1]) if len(sys.argv) > 1 else 60.0
    repeat = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    print(f"{seconds:g} s of SMPL-H (52 joints) to 30 fps, best of {repeat}")
    print("| input | method | frames | largest clock gap | largest error vs slerp at k/30 s | time |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as d:
        for label, rate, stride in [("120", Fraction(120), 4), ("59.94", Fraction(60000, 1001), 2)]:
            n = int(seconds * rate) + 1
            path, out = Path(d) / "in.npz", Path(d) / "out.npz"
            src = make(path, n, float(label))
            m = int(Fraction(n - 1) / rate * 30) + 1
            exact = [Fraction(k, 30) for k in range(m)]

            def stride_loop():
                with np.load(path) as z:
                    return z["poses"][::stride].copy()

            t_stride, strided = best(stride_loop, repeat)
            taken = [Fraction(stride * k) / rate for k in range(len(strided))]
            gap = max(abs(float(a - b)) for a, b in zip(taken, exact))
            k = min(len(strided), len(exact))
            err = worst_degrees(src, rate, exact[:k], strided[:k])
            print(f"| {label} fps | `poses[::{stride}]` | {len(strided)} | {gap:.6f} s | "
                  f"{err:.4f}° | {t_stride * 1e3:.1f} ms |")
            t_ib, _ = best(lambda: inbetween.resample_amass(path, out, 30), repeat)
            with np.load(out) as z:
                ours = z["poses"].copy()
            err = worst_degrees(src, rate, exact, ours)
            print(f"| {label} fps | `inbetween.resample_amass` | {len(ours)} | 0 | "
                  f"{err:.4f}° | {t_ib * 1e3:.1f} ms |")


if __name__ == "__main__":
    main()
