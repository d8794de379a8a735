"""Times `inbetween interp` against scipy and numpy-quaternion doing the same job, whole process,
in one run, and prints medians and ratios. Called by run.sh (see there).

Workload: 1 001 keys one second apart (turning about changing axes), every frame at 1000 fps:
10⁶ frames (--frames sets the total). Every contender writes the same CSV columns
`frame,time,w,x,y,z` to a file in a temporary directory:

- scipy Slerp + numpy.savetxt('%.9f')        (the baseline of the ratios)
- scipy RotationSpline + savetxt('%.9f')
- numpy-quaternion squad + savetxt('%.9f')
- inbetween hermite: shortest round-trip CSV, --precision 9, and npy

Also: peak RSS of inbetween at 10⁶ and 10⁷ frames, and start-up plus a 10-key file.
"""
import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import textwrap
import time

PY_PRELUDE = """
import numpy as np, sys
keys = np.loadtxt(sys.argv[1], delimiter=',', skiprows=1)
t_keys, q_keys = keys[:, 0], keys[:, 1:5]            # w, x, y, z
fps = float(sys.argv[3])
n = int(round((t_keys[-1] - t_keys[0]) * fps)) + 1
frames = np.arange(n)
times = frames / fps
"""

SCIPY_SLERP = PY_PRELUDE + """
from scipy.spatial.transform import Rotation as R, Slerp
rot = R.from_quat(q_keys[:, [1, 2, 3, 0]])
q = Slerp(t_keys, rot)(times).as_quat()[:, [3, 0, 1, 2]]
np.savetxt(sys.argv[2], np.column_stack([frames, times, q]), fmt='%.9f', delimiter=',',
           header='frame,time,w,x,y,z', comments='')
"""

SCIPY_SPLINE = PY_PRELUDE + """
from scipy.spatial.transform import Rotation as R, RotationSpline
rot = R.from_quat(q_keys[:, [1, 2, 3, 0]])
q = RotationSpline(t_keys, rot)(times).as_quat()[:, [3, 0, 1, 2]]
np.savetxt(sys.argv[2], np.column_stack([frames, times, q]), fmt='%.9f', delimiter=',',
           header='frame,time,w,x,y,z', comments='')
"""

NPQ_SQUAD = PY_PRELUDE + """
import quaternion
qs = quaternion.as_quat_array(q_keys)
qs = quaternion.unflip_rotors(qs)
q = quaternion.as_float_array(quaternion.squad(qs, t_keys, times))
np.savetxt(sys.argv[2], np.column_stack([frames, times, q]), fmt='%.9f', delimiter=',',
           header='frame,time,w,x,y,z', comments='')
"""


def keys_csv(path, segments):
    import math
    with open(path, "w") as f:
        f.write("time,w,x,y,z\n")
        for i in range(segments + 1):
            a = float(i)
            ax = [math.sin(0.31 * a), math.cos(0.7 * a), 0.5]
            n = math.sqrt(sum(c * c for c in ax))
            ang = 0.3 + 0.5 * math.sin(0.13 * a) + 0.2 * a
            s = math.sin(ang / 2)
            f.write(f"{a},{math.cos(ang / 2)!r},{s * ax[0] / n!r},{s * ax[1] / n!r},{s * ax[2] / n!r}\n")


def run(cmd):
    """Wall time and peak RSS (MiB) of one process."""
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(p.pid, 0)
    dt = time.perf_counter() - t0
    err = p.stderr.read().decode()
    p.stderr.close()
    if status != 0:
        sys.exit(f"{cmd} failed: {err}")
    return dt, usage.ru_maxrss / 1024


def median_run(cmd, repeat):
    times, rss = zip(*(run(cmd) for _ in range(repeat)))
    return statistics.median(times), max(rss)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--frames", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=5)
    a = ap.parse_args()
    fps = 1000
    segments = a.frames // fps
    tmp = tempfile.mkdtemp(prefix="inbetween-compare-")
    keys = os.path.join(tmp, "keys.csv")
    keys_csv(keys, segments)
    out = os.path.join(tmp, "out")
    py = sys.executable
    scripts = {}
    for name, src in [("scipy_slerp", SCIPY_SLERP), ("scipy_spline", SCIPY_SPLINE), ("npq_squad", NPQ_SQUAD)]:
        scripts[name] = os.path.join(tmp, name + ".py")
        with open(scripts[name], "w") as f:
            f.write(src)
    n_frames = segments * fps + 1
    contenders = [
        ("scipy Slerp + savetxt('%.9f')", [py, scripts["scipy_slerp"], keys, out + ".csv", str(fps)]),
        ("scipy RotationSpline + savetxt", [py, scripts["scipy_spline"], keys, out + ".csv", str(fps)]),
        ("numpy-quaternion squad + savetxt", [py, scripts["npq_squad"], keys, out + ".csv", str(fps)]),
        ("inbetween hermite, CSV shortest", [a.bin, "interp", keys, "--fps", str(fps), "-o", out + ".csv"]),
        ("inbetween hermite, CSV --precision 9", [a.bin, "interp", keys, "--fps", str(fps), "--precision", "9", "-o", out + ".csv"]),
        ("inbetween hermite, npy", [a.bin, "interp", keys, "--fps", str(fps), "--output-format", "npy", "-o", out + ".npy"]),
    ]
    print(f"workload: {segments} segments x {fps} in-betweens = {n_frames} frames; "
          f"median of {a.repeat} whole-process runs; same run, same machine")
    results = []
    for name, cmd in contenders:
        t, rss = median_run(cmd, a.repeat)
        results.append((name, t, rss))
    base = results[0][1]
    print(f"{'contender':40} {'median s':>9} {'frames/s':>12} {'peak MiB':>9} {'vs scipy Slerp':>15}")
    for name, t, rss in results:
        print(f"{name:40} {t:9.3f} {n_frames / t / 1e6:10.2f} M {rss:9.1f} {base / t:14.1f}x")

    # Peak memory does not grow with the output: the same keys at 10x the rate (10x the frames).
    _, rss1 = run([a.bin, "interp", keys, "--fps", str(fps), "-o", out + ".csv"])
    _, rss10 = run([a.bin, "interp", keys, "--fps", str(10 * fps), "-o", out + ".csv"])
    print(f"inbetween peak RSS: {rss1:.1f} MiB at {n_frames} frames, {rss10:.1f} MiB at {10 * (n_frames - 1) + 1} frames (same keys, 10x the rate)")

    # Start-up plus a 10-key file.
    small = os.path.join(tmp, "keys10k.csv")
    keys_csv(small, 9)
    ts = sorted(run([a.bin, "interp", small, "--fps", "30", "-o", out + "_small.csv"])[0] for _ in range(51))
    print(f"inbetween start-up + 10 keys at 30 fps: median {statistics.median(ts) * 1e3:.2f} ms over 51 runs")


if __name__ == "__main__":
    main()
