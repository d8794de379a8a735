"""Thinned motion capture: how well an interpolating scheme rebuilds real BVH motion from every
k-th frame, against scipy's RotationSpline. Run by hand, not in CI (run.sh makes the venv):

    bash benches/compare/thinned/run.sh --set held-out [--bin PATH] [--extra "--scheme bezier"]
    python thinned.py [--bin PATH] [--extra ARGS] [--ks 2,4,8,16] [--out FILE] CLIP.bvh|DIR ...

For each clip, joint and k: the keys are frames 0, k, 2k, ... up to the last multiple of k; every
original frame between the first and last key is rebuilt (1) by scipy
`RotationSpline(key_times, key_rotations)` per joint and (2) by one call per clip and k of
`inbetween interp KEYS.csv --key-fps RATE --fps RATE -o out.csv EXTRA` on a CSV of all joints
(`track,frame,w,x,y,z`, integer frame numbers at the clip's exact rate, so keys and output frames
sit exactly on the original frame times). Error = rotation angle (rad) between rebuilt and original
local rotation, sign-blind; key frames (exact) are left out of the means. "all" pools every joint
and non-key frame of every clip; "interior" only the frames more than two key intervals (2k
frames) from either end key (away from the end conditions). A joint's rotation is its rotation
channels in file order, intrinsic, degrees (`Zrotation Xrotation Yrotation` = scipy
from_euler('ZXY')); each clip's conversion is first checked against `inbetween interp CLIP.bvh`
(<= 1e-9 rad at every frame) and its rate against the times the tool writes.
"""
import argparse
import os
import shlex
import subprocess
import sys
import tempfile
import time
from fractions import Fraction

import numpy as np
from scipy.spatial.transform import Rotation, RotationSpline

STANDARD_RATES = [12, 15, 24, 25, 30, 48, 50, 60, 90, 100, 120, 240]


def clip_rate(frame_time):
    """docs/spec.md §3 BVH: the nearest standard rate (and /1001 ratio) within 1e-4 relative,
    else the decimal as written, exactly."""
    exact = 1 / Fraction(frame_time)
    cands = [Fraction(r) for r in STANDARD_RATES] + [Fraction(r * 1000, 1001) for r in STANDARD_RATES]
    best = min(cands, key=lambda r: abs(r - exact))
    return best if abs(best - exact) <= Fraction(1, 10000) * best else exact


def read_bvh(path):
    """-> (rate as a Fraction, (frames, tracks, 4) quaternions w,x,y,z): one track per joint with
    channels, in file order; a joint with no rotation channel is the identity."""
    with open(path) as f:
        lines = [l.split() for l in f.read().splitlines()]
    joints, col, i = [], 0, 0  # joints: (rotation letters, rotation columns)
    while not lines[i] or lines[i][0].upper() != "MOTION":
        t = lines[i]
        if t and t[0].upper() == "CHANNELS":
            chans = t[2:2 + int(t[1])]
            rot = [(c[0].upper(), col + n) for n, c in enumerate(chans) if c.lower().endswith("rotation")]
            joints.append(("".join(a for a, _ in rot), [c for _, c in rot]))
            col += len(chans)
        i += 1
    rows, frame_time = [], None
    for t in lines[i + 1:]:
        if not t or t[0].startswith("Frames"):
            continue
        if t[0] == "Frame" and t[1].startswith("Time"):
            frame_time = t[-1]
            continue
        rows.append([float(x) for x in t])
    motion = np.array(rows)
    assert motion.shape[1] == col, (path, motion.shape, col)
    q = np.zeros((len(motion), len(joints), 4))
    for j, (seq, cols) in enumerate(joints):
        if seq:
            q[:, j] = Rotation.from_euler(seq, motion[:, cols], degrees=True).as_quat(scalar_first=True)
        else:
            q[:, j, 0] = 1.0
    return clip_rate(frame_time), q


def angle(a, b):
    """Rotation angle (rad) between unit quaternions a and b (..., 4), either sign: 2·acos(|a·b|),
    computed as 4·atan2(|a − sb|, |a + sb|), s = sign(a·b), which keeps precision near 0."""
    s = np.where(np.sum(a * b, axis=-1) < 0, -1.0, 1.0)[..., None]
    return 4 * np.arctan2(np.linalg.norm(a - s * b, axis=-1), np.linalg.norm(a + s * b, axis=-1))


def fps_arg(rate):
    return str(rate.numerator) if rate.denominator == 1 else f"{rate.numerator}/{rate.denominator}"


def run_interp(binary, args, out):
    """Runs `binary interp ARGS -o out` and reads the CSV: (tracks in order, frames, times, q)
    with q (tracks, frames, 4), w,x,y,z. The output is track-major, every track on the same frames."""
    p = subprocess.run([binary, "interp", *args, "-o", out], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{binary} interp {' '.join(args)}: exit {p.returncode}\n{p.stderr}")
    with open(out) as f:
        header = [h.strip() for h in f.readline().split(",")]
    cols = [header.index(c) for c in ("frame", "time", "w", "x", "y", "z")]
    data = np.loadtxt(out, delimiter=",", skiprows=1, usecols=cols, ndmin=2)
    names = np.loadtxt(out, delimiter=",", skiprows=1, usecols=[header.index("track")], dtype=str, ndmin=1)
    tracks = list(dict.fromkeys(names))
    m = len(data) // len(tracks)
    assert m * len(tracks) == len(data) and all((names[t * m:(t + 1) * m] == n).all()
                                                 for t, n in enumerate(tracks)), out
    data = data.reshape(len(tracks), m, 6)
    assert (data[:, :, :2] == data[:1, :, :2]).all(), out  # every track on the same frames
    return tracks, data[0, :, 0], data[0, :, 1], data[:, :, 2:]


def check_conversion(binary, path, rate, q, work):
    """The tool's own reading of the clip (every frame a key) must equal ours to 1e-9 rad, on the
    same frame times."""
    tracks, frames, times, tq = run_interp(binary, [path], os.path.join(work, "full.csv"))
    assert len(tracks) == q.shape[1], (path, len(tracks), q.shape)
    assert (frames == np.arange(len(q))).all(), (path, "frames")
    assert np.allclose(times, frames / float(rate), rtol=1e-14, atol=0), (path, "rate", rate)
    err = angle(tq, q.transpose(1, 0, 2)).max()
    assert err <= 1e-9, (path, "conversion off by", err)
    return err


def thin(binary, extra, rate, q, k, work):
    """-> (frame numbers rebuilt, scipy error, inbetween error), errors (frames, tracks), rad."""
    last = (len(q) - 1) // k * k
    keys = np.arange(0, last + 1, k)
    frames = np.arange(last + 1)
    t_keys, t_all = keys / float(rate), frames / float(rate)
    sp = np.empty((len(frames), q.shape[1], 4))
    for j in range(q.shape[1]):
        spline = RotationSpline(t_keys, Rotation.from_quat(q[keys, j], scalar_first=True))
        sp[:, j] = spline(t_all).as_quat(scalar_first=True)
    keys_csv = os.path.join(work, f"keys{k}.csv")
    with open(keys_csv, "w") as f:
        f.write("track,frame,w,x,y,z\n")
        for j in range(q.shape[1]):
            for fr in keys:
                f.write(f"t{j},{fr}," + ",".join(repr(float(v)) for v in q[fr, j]) + "\n")
    r = fps_arg(rate)
    tracks, out_frames, out_times, tq = run_interp(
        binary, [keys_csv, "--key-fps", r, "--fps", r, *extra], os.path.join(work, f"out{k}.csv"))
    assert tracks == [f"t{j}" for j in range(q.shape[1])], "track order"
    assert (out_frames == frames).all(), ("output frames", out_frames[:3], out_frames[-3:], last)
    assert np.allclose(out_times, t_all, rtol=1e-14, atol=0), "output times"
    orig = q[: last + 1]
    return frames, angle(sp, orig), angle(tq.transpose(1, 0, 2), orig)


def table(rows, header):
    w = [max(len(str(x)) for x in col) for col in zip(header, *rows)]
    fmt = lambda r: "| " + " | ".join(str(x).rjust(n) for x, n in zip(r, w)) + " |"
    return "\n".join([fmt(header), "|" + "|".join("-" * (n + 2) for n in w) + "|"] + [fmt(r) for r in rows])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("inputs", nargs="+", help="BVH files or folders of them")
    ap.add_argument("--bin", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "target", "release", "inbetween"))
    ap.add_argument("--extra", default="", help="more arguments for interp, e.g. '--scheme bezier'")
    ap.add_argument("--ks", default="2,4,8,16")
    ap.add_argument("--command", help="the command line to print at the top")
    ap.add_argument("--out", help="also write the report to this file")
    a = ap.parse_args()
    ks = [int(k) for k in a.ks.split(",")]
    extra = shlex.split(a.extra)
    paths = []
    for p in a.inputs:
        paths += sorted(os.path.join(p, f) for f in os.listdir(p) if f.lower().endswith(".bvh")) \
            if os.path.isdir(p) else [p]
    out = []
    say = lambda s="": (out.append(s), print(s, flush=True))
    version = subprocess.run([a.bin, "--version"], capture_output=True, text=True).stdout.strip()
    say(f"# command: {a.command or ' '.join(map(shlex.quote, sys.argv))}")
    say(f"# binary: {a.bin} ({version}); interp extra args: {a.extra or '(none)'}")
    say(f"# numpy {np.__version__}, scipy {__import__('scipy').__version__}; errors in rad, "
        "mean over non-key frames; ratio = inbetween / scipy RotationSpline")
    t0 = time.time()
    # sums[k][clip] = [n, scipy, inbetween, n_interior, scipy_interior, inbetween_interior]
    sums = {k: {} for k in ks}
    clips = []
    with tempfile.TemporaryDirectory(prefix="thinned-") as work:
        for path in paths:
            name = os.path.basename(path)
            rate, q = read_bvh(path)
            conv = check_conversion(a.bin, path, rate, q, work)
            clips.append(name)
            say(f"# {name}: {len(q)} frames, {q.shape[1]} joints, {fps_arg(rate)} fps, "
                f"conversion within {conv:.1e} rad of the tool's")
            for k in ks:
                if (len(q) - 1) // k < 1:
                    continue
                frames, es, ei = thin(a.bin, extra, rate, q, k, work)
                last = frames[-1]
                nonkey = frames % k != 0
                inner = nonkey & (frames > 2 * k) & (frames < last - 2 * k)
                sums[k][name] = [nonkey.sum() * q.shape[1], es[nonkey].sum(), ei[nonkey].sum(),
                                 inner.sum() * q.shape[1], es[inner].sum(), ei[inner].sum()]
    say()
    say(f"## Pooled over {len(clips)} clips (all joints, non-key frames)")
    say()
    rows = []
    for k in ks:
        n, s, i, ni, si, ii = np.sum(list(sums[k].values()), axis=0)
        rows.append([k, int(n), f"{s / n:.6f}", f"{i / n:.6f}", f"{i / s:.4f}", f"{100 * (i / s - 1):+.1f} %",
                     int(ni), f"{si / ni:.6f}" if ni else "-", f"{ii / ni:.6f}" if ni else "-",
                     f"{ii / si:.4f}" if ni else "-", f"{100 * (ii / si - 1):+.1f} %" if ni else "-"])
    say(table(rows, ["k", "samples", "scipy", "inbetween", "ratio", "vs scipy", "interior samples",
                     "scipy int.", "inbetween int.", "ratio int.", "vs scipy int."]))
    say()
    say("## Per clip: ratio inbetween / scipy (all non-key frames)")
    say()
    rows = [[c] + [f"{sums[k][c][2] / sums[k][c][1]:.3f}" if c in sums[k] else "-" for k in ks] for c in clips]
    rows.append(["geometric mean"] + [f"{np.exp(np.mean([np.log(v[2] / v[1]) for v in sums[k].values()])):.3f}"
                                      for k in ks])
    say(table(rows, ["clip"] + [f"k={k}" for k in ks]))
    say()
    say(f"# wall time {time.time() - t0:.1f} s")
    if a.out:
        with open(a.out, "w") as f:
            f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
