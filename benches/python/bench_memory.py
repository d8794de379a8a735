"""Peak memory of one `resample` or `Curve.__call__` against the size of its result
(docs/performance.md, issue 48).

    python benches/python/bench_memory.py resample|velocity|curve

`resample`: 60 joints x 72 000 frames (10 minutes at 120 fps) onto 100 fps, (60 000, 60, 4);
`velocity`: the same with velocity=True; `curve`: `Curve` through 1001 keys evaluated at 10^7
sorted times. The inputs are built a slice at a time, so that the peak before the call is the
process's current size; the figure is the rise of ru_maxrss over the call, against the bytes of
the result. Needs numpy, scipy and the installed `inbetween` package; Linux (ru_maxrss in KiB).
"""

import gc
import resource
import sys
import time

import numpy as np
from scipy.spatial.transform import Rotation

import inbetween


def peak():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def main():
    case = sys.argv[1] if len(sys.argv) > 1 else "resample"
    if case in ("resample", "velocity"):
        frames, joints = 72_000, 60
        clip = np.empty((frames, joints, 4))
        j = np.arange(joints)[None, :]
        for a in range(0, frames, 2000):
            tt = np.arange(a, min(a + 2000, frames))[:, None] / 120.0
            rv = np.stack([0.6 * np.sin(1.3 * tt + 0.1 * j), 0.4 * np.cos(0.7 * tt - 0.2 * j),
                           0.3 * np.sin(2.1 * tt + 0.05 * j)], axis=-1)
            clip[a:a + len(tt)] = Rotation.from_rotvec(rv.reshape(-1, 3)).as_quat(
                scalar_first=True).reshape(len(tt), joints, 4)
        call = lambda: inbetween.resample(clip, 120, 100, velocity=case == "velocity")
    elif case == "curve":
        rng = np.random.default_rng(1)
        times = np.cumsum(rng.uniform(0.02, 0.05, 1001))
        q = Rotation.random(1001, random_state=2).as_quat(scalar_first=True)
        t = np.linspace(times[0], times[-1], 10_000_000)
        curve = inbetween.Curve(times, q)
        call = lambda: curve(t)
    else:
        sys.exit(f"expected resample, velocity or curve, found {case!r}")
    gc.collect()
    before = peak()
    start = time.perf_counter()
    out = call()
    took = time.perf_counter() - start
    rise = peak() - before
    result = sum(o.nbytes for o in out) if isinstance(out, tuple) else out.nbytes
    print(f"{case}: result {result / 1e6:.0f} MB, peak rise {rise / 1e6:.0f} MB "
          f"(result + {(rise - result) / 2**20:.0f} MiB), {took:.3f} s")


if __name__ == "__main__":
    main()
