"""Times `inbetween interp clip.bvh --fps 60 -o out.bvh` against bvhio doing the same job
(bvhio_resample.py), whole process, alternating, in one run, and prints medians, the ratio and
peak memory against the targets of issue 14. Called by run.sh (see there).

Each run is one process; its wall time is measured around it and its peak RSS is the
`ru_maxrss` that `os.wait4` returns for it (the Python side's includes the interpreter and its
imports). Runs alternate inbetween, bvhio, inbetween, bvhio, ... so that drift on this shared
machine hits both alike; the ratio is of the two medians (the median of the per-pair ratios is
printed beside it).
"""
import argparse
import os
import shutil
import statistics
import subprocess
import sys
import time

MIB = 1024 * 1024


def run(cmd, fails=False):
    """Wall time (s) and peak RSS (bytes) of one process (`fails`: it must exit with 2)."""
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(p.pid, 0)
    dt = time.perf_counter() - t0
    err = p.stderr.read().decode()
    p.stderr.close()
    if os.waitstatus_to_exitcode(status) != (2 if fails else 0):
        sys.exit(f"{' '.join(cmd)} failed: {err}")
    return dt, usage.ru_maxrss * 1024  # Linux: KiB


def motion_header(path):
    """(Frames, Frame Time) as written in a BVH file."""
    frames = frame_time = None
    with open(path) as f:
        for line in f:
            if line.startswith("Frames:"):
                frames = int(line.split()[1])
            elif line.startswith("Frame Time:"):
                frame_time = line.split()[2]
                break
    return frames, frame_time


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--clip", required=True)
    ap.add_argument("--outdir", required=True)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--stages", action="store_true",
                    help="instead: where inbetween's time and memory go (see stages())")
    a = ap.parse_args()
    if a.stages:
        return stages(a)
    here = os.path.dirname(os.path.abspath(__file__))
    size = os.path.getsize(a.clip)
    ours_out = os.path.join(a.outdir, "inbetween60.bvh")
    py_out = os.path.join(a.outdir, "bvhio60.bvh")
    contenders = {
        "inbetween": [a.bin, "interp", a.clip, "--fps", "60", "-o", ours_out],
        "bvhio": [sys.executable, os.path.join(here, "bvhio_resample.py"), a.clip, py_out],
    }
    frames, frame_time = motion_header(a.clip)
    print(f"clip: {a.clip}: {size / MIB:.1f} MiB, {frames} frames, Frame Time {frame_time}")
    print(f"{a.repeat} runs each, alternating, whole process, one run of this script")
    res = {name: [] for name in contenders}
    for i in range(a.repeat):
        for name, cmd in contenders.items():
            t, rss = run(cmd)
            res[name].append((t, rss))
            print(f"  run {i + 1} {name:9} {t:8.3f} s  peak {rss / MIB:7.1f} MiB", flush=True)

    for name, out in (("inbetween", ours_out), ("bvhio", py_out)):
        f, ft = motion_header(out)
        print(f"{name} output: {os.path.getsize(out) / MIB:.1f} MiB, Frames: {f}, Frame Time: {ft}")

    med = {n: statistics.median(t for t, _ in r) for n, r in res.items()}
    peak = {n: max(m for _, m in r) for n, r in res.items()}
    pair = statistics.median(b[0] / o[0] for o, b in zip(res["inbetween"], res["bvhio"]))
    budget = 2 * size + 64 * MIB
    ratio = med["bvhio"] / med["inbetween"]
    print(f"{'':10} {'median s':>9} {'min s':>8} {'max s':>8} {'peak MiB':>9}")
    for n in contenders:
        ts = [t for t, _ in res[n]]
        print(f"{n:10} {med[n]:9.3f} {min(ts):8.3f} {max(ts):8.3f} {peak[n] / MIB:9.1f}")
    print(f"speed-up (bvhio median / inbetween median): {ratio:.1f}x "
          f"(median of per-pair ratios {pair:.1f}x); target >= 20x: {'met' if ratio >= 20 else 'MISSED'}")
    print(f"inbetween peak RSS {peak['inbetween'] / MIB:.1f} MiB = {peak['inbetween'] / size:.2f}x the file; "
          f"budget 2x file + 64 MiB = {budget / MIB:.1f} MiB: "
          f"{'met' if peak['inbetween'] <= budget else 'MISSED'}")


def stages(a):
    """Where inbetween's time and memory go, without a profiler and without changing it: the
    same command cut short at successive points, alternating, medians of --repeat.

    1. parse: the clip with a bad last row, so the tool stops with an input error once the whole
       file is read and every number parsed (text + the clip's values, before any track exists);
    2. + tracks: --max-frames 1, refused after the document and the tracks are built, before any
       curve;
    3. + curves: --fps 1, every curve built, 601 frames written;
    4. whole: --fps 60, 36 000 frames written.

    Written for the document path. Since the lean BVH path (docs/performance.md), an input error
    or --max-frames sends the run to the document path after the lean read, so stages 1 and 2
    measure the lean read plus the document path up to that point; stages 3 and 4 are the lean
    path. Kept to reproduce the "before" figures (git checkout the commit before the lean path).
    """
    bad = os.path.join(a.outdir, "bad_last_row.bvh")
    # Copied in pieces: a child's ru_maxrss can include this process's own peak (a vfork child
    # execs from the parent's memory), so this process must stay small.
    with open(a.clip, "rb") as src, open(bad, "wb") as dst:
        shutil.copyfileobj(src, dst)
        dst.write(b"abc\n")
    out = os.path.join(a.outdir, "stage.bvh")
    cmds = [
        ("parse (error at the last row)", [a.bin, "interp", bad, "--fps", "60", "-o", out], True),
        ("+ document and tracks (--max-frames 1)",
         [a.bin, "interp", a.clip, "--fps", "60", "--max-frames", "1", "-o", out], True),
        ("+ curves (--fps 1: 601 frames)", [a.bin, "interp", a.clip, "--fps", "1", "-o", out], False),
        ("whole (--fps 60: 36000 frames)", [a.bin, "interp", a.clip, "--fps", "60", "-o", out], False),
    ]
    res = {name: [] for name, _, _ in cmds}
    for _ in range(a.repeat):
        for name, cmd, fails in cmds:
            res[name].append(run(cmd, fails))
    os.remove(bad)
    print(f"inbetween by stage, medians of {a.repeat}, alternating :")
    for name, _, _ in cmds:
        t = statistics.median(x for x, _ in res[name])
        m = max(x for _, x in res[name])
        print(f"  {name:42} {t:7.3f} s  peak {m / MIB:7.1f} MiB")


if __name__ == "__main__":
    main()
