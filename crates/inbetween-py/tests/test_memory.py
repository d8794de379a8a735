"""Peak memory of `resample` and `Curve.__call__` (issue 48): the rise of the process's peak
resident set over one call stays within the result plus a margin (64 MiB for `resample`, the
issue's bound; 16 MiB for `Curve.__call__`, whose times are read in place).

Each call runs in a fresh interpreter whose inputs are built in slices (no large temporaries),
with the peak reset to the current size before the call where Linux allows it
(/proc/self/clear_refs), so that the peak after the call is the call's own."""

import json
import subprocess
import sys

import pytest

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                reason="ru_maxrss in KiB and /proc/self: Linux")

MIB = 1 << 20

MEASURE = r"""
import gc, json, resource, sys
import numpy as np
import inbetween

def peak():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024

def current():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * resource.getpagesize()

def quats(frames, joints):
    # Unit quaternions about a moving axis, built a slice at a time.
    q = np.empty((frames, joints, 4))
    j = np.arange(joints)[None, :]
    for a in range(0, frames, 4096):
        t = np.arange(a, min(a + 4096, frames))[:, None] / 120.0
        angle = 0.6 * np.sin(1.3 * t + 0.1 * j)
        axis = np.stack([np.sin(0.7 * t + j), np.cos(0.7 * t + j), 0.5 + 0 * t * j], axis=-1)
        axis /= np.linalg.norm(axis, axis=-1, keepdims=True)
        q[a:a + len(t), :, 0] = np.cos(angle / 2)
        q[a:a + len(t), :, 1:] = np.sin(angle / 2)[..., None] * axis
    return q

case = sys.argv[1]
if case == "resample":
    clip = quats(60_000, 64)
    call = lambda: inbetween.resample(clip, 120, 100, velocity=True)
else:
    keys = quats(1001, 1)[:, 0]
    times = np.arange(1001) * 0.03
    curve = inbetween.Curve(times, keys)
    t = np.linspace(0.0, times[-1], 4_000_000)
    call = lambda: curve(t)
gc.collect()
try:
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")
except OSError:
    pass
before = max(peak(), current())
out = call()
rise = peak() - before
result = sum(o.nbytes for o in out) if isinstance(out, tuple) else out.nbytes
print(json.dumps({"rise": rise, "result": result, "before": before, "current": current()}))
"""


def measure(case):
    done = subprocess.run([sys.executable, "-c", MEASURE, case], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_resample_peak_is_the_result_and_little_more():
    m = measure("resample")
    assert m["result"] >= 100e6  # 50 000 frames x 64 joints x (4 + 3) float64
    assert m["rise"] <= m["result"] + 64 * MIB, m


def test_curve_call_peak_is_the_result_and_little_more():
    m = measure("curve")
    assert m["result"] >= 100e6  # 4e6 times x 4 float64
    assert m["rise"] <= m["result"] + 16 * MIB, m
