"""Keys kept by `inbetween reduce` on real motion capture, against the slerp-greedy rule and
glTF-Transform's `resample()` rule (issue 15, docs/spec.md §4.7). Called by run.sh (see there);
the figures are in docs/reduce.md.

Per clip (BVH; tracks = joints with rotation channels, as `inbetween` reads them) and per
tolerance T (degrees, geodesic angle):

- dense frames: each joint's Euler channels turned into quaternions by scipy
  (`Rotation.from_euler` with the joint's channel order, upper case = intrinsic, degrees), signs
  made continuous along the track. Independent of inbetween's reader: the replays below compare
  inbetween's curves with these frames.
- slerp-greedy (written here from its definition): from the last key, walk forward; the segment
  last key..j is accepted while every frame inside is within T of the slerp between its two
  ends; at the first j that fails, frame j-1 becomes a key and the walk restarts there. The last
  frame is a key. Its error is at most T by construction (checked).
- gltf-transform (angle): glTF-Transform's `resample()` rule for rotation channels, as in
  keyframe-resample's `resample()` (the JavaScript path glTF-Transform uses by default,
  `resampleDebug`): for each frame i (1..n-2) in order, compare frame i with the slerp, at i's
  time, between the LAST KEPT frame and frame i+1 (one frame of look-ahead, gl-matrix slerp); keep
  i if it misses, or if the angles last-kept→i→i+1 add up to π or more; the last frame is always
  kept. Its test is per component (|Δ| ≤ tolerance on each of the 4 quaternion components); this
  row uses the geodesic angle ≤ T instead, so that the rule runs at the same tolerance.
- gltf-transform (components): the same rule with its own per-component test, at component
  tolerance sin(T/4) (then one frame passing the test is within T: |Δq| ≤ 2·sin(T/4)), on the
  frames rounded to float32 as in a glTF accessor.
  For both glTF rows the real error is measured: slerp between the kept keys, at every frame.
- inbetween: `inbetween reduce CLIP --tolerance T --scheme S --method M [--no-velocities]
  --translation-tolerance 1e9 -o keys.json` (BVH roots carry positions; 1e9 length units means
  they never force a key, so every key is there for a rotation). Keys counted per track in
  keys.json. With --replay, the keys (translations dropped) go through `inbetween interp --scheme
  S --output-format npy` at the clip's rate and every frame is compared with the dense frames
  above: the independent measure of the guarantee.

Ratios are keys kept / slerp-greedy keys at the same T, pooled (sums over every track of every
clip). Tracks that never move count too (2 keys for every rule).

Output: a markdown table on stdout (pooled), per-clip figures, and everything as JSON (--json).
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.spatial.transform import Rotation

CLIPS = ["01_01", "01_03", "Boxing_Toes", "test", "test2", "test3", "test_mocapbank", "test_freebvh"]
DEFAULT_CONFIGS = [
    "bezier:greedy:vel", "bezier:greedy:novel", "hermite:greedy:vel", "hermite:greedy:novel",
    "slerp:greedy:novel",
]


# ---------------------------------------------------------------------------------------------
# BVH


def read_bvh(path):
    """Joints with rotation channels: [(name, order 'ZXY', column indices)], motion (frames×cols),
    frame time (as written), header lines (up to and including MOTION)."""
    with open(path) as f:
        text = f.read()
    lines = text.splitlines()
    m = next(i for i, l in enumerate(lines) if l.strip().upper() == "MOTION")
    header = lines[: m + 1]
    joints, col, name = [], 0, None
    for line in header:
        tok = line.split()
        if not tok:
            continue
        if tok[0] in ("ROOT", "JOINT"):
            name = tok[1]
        elif tok[0] == "End":
            name = None
        elif tok[0] == "CHANNELS":
            k = int(tok[1])
            ch = tok[2 : 2 + k]
            rot = [(c[0].upper(), col + i) for i, c in enumerate(ch) if c.lower().endswith("rotation")]
            if rot:
                joints.append((name, "".join(r[0] for r in rot), [r[1] for r in rot]))
            col += k
    frame_time = None
    rows = []
    for line in lines[m + 1 :]:
        s = line.strip()
        if not s:
            continue
        if s.startswith("Frames"):
            continue
        if s.startswith("Frame Time"):
            frame_time = s.split(":", 1)[1].strip()
            continue
        rows.append(s)
    motion = np.array([[float(x) for x in r.split()] for r in rows])
    assert motion.shape[1] == col, (path, motion.shape, col)
    return joints, motion, frame_time, header


def write_trimmed(path, out, first, count):
    """Frames first..first+count-1 of a BVH file, as a BVH file."""
    with open(path) as f:
        lines = f.read().splitlines()
    m = next(i for i, l in enumerate(lines) if l.strip().upper() == "MOTION")
    rest = [l for l in lines[m + 1 :] if l.strip()]
    ft = next(l for l in rest if l.strip().startswith("Frame Time"))
    rows = [l for l in rest if not l.strip().startswith(("Frames", "Frame Time"))]
    rows = rows[first : first + count]
    with open(out, "w") as f:
        f.write("\n".join(lines[: m + 1] + [f"Frames: {len(rows)}", ft.strip()] + rows) + "\n")


def dense_quats(order, angles_deg):
    """(n, 4) w,x,y,z, intrinsic Euler in the channels' order, signs continuous."""
    xyzw = Rotation.from_euler(order, angles_deg, degrees=True).as_quat()
    q = xyzw[:, [3, 0, 1, 2]]
    return continuous(q)


def continuous(q):
    q = q.copy()
    for i in range(1, len(q)):
        if np.dot(q[i], q[i - 1]) < 0:
            q[i] = -q[i]
    return q


# ---------------------------------------------------------------------------------------------
# Geometry (numpy, float64)


def angle(a, b):
    """Rotation angle (rad) between unit quaternions a and b (any leading shape), sign-blind:
    4·asin(|a ∓ b|/2), exact near zero."""
    s = np.sign(np.sum(a * b, axis=-1, keepdims=True))
    s[s == 0] = 1
    c = np.linalg.norm(a - s * b, axis=-1)
    return 4 * np.arcsin(np.minimum(1.0, c / 2))


def slerp(a, b, u):
    """Slerp from a to b (the shorter way) at u; a, b (..., 4), u (...)."""
    d = np.sum(a * b, axis=-1)
    b = np.where((d < 0)[..., None], -b, b)
    d = np.abs(d)
    om = np.arccos(np.minimum(1.0, d))
    so = np.sin(om)
    small = so < 1e-12
    so_safe = np.where(small, 1.0, so)
    w0 = np.where(small, 1 - u, np.sin((1 - u) * om) / so_safe)
    w1 = np.where(small, u, np.sin(u * om) / so_safe)
    r = w0[..., None] * a + w1[..., None] * b
    return r / np.linalg.norm(r, axis=-1, keepdims=True)


def slerp_replay(q, keys):
    """Max and per-frame error of slerp between the kept frames `keys` (sorted, 0 and n-1)."""
    n = len(q)
    k = np.asarray(keys)
    i = np.arange(n)
    seg = np.clip(np.searchsorted(k, i, side="right") - 1, 0, len(k) - 2)
    a, b = k[seg], k[seg + 1]
    u = (i - a) / (b - a)
    e = angle(slerp(q[a], q[b], u), q)
    return e


def slerp_greedy(q, tol):
    """Keys of the slerp-greedy rule (see the module docstring). Candidate ends are tested in
    blocks (vectorised); the result is that of the frame-by-frame walk."""
    n = len(q)
    keys = [0]
    s = 0
    budget = 500_000
    while s < n - 1:
        e = s + 2
        grow = 8
        nxt = None
        while e <= n - 1:
            hi_limit = n - 1
            L = min(hi_limit, e + grow - 1) - s  # frames s+1 .. emax-1 at most
            B = max(1, min(grow, budget // max(L, 1), hi_limit - e + 1))
            E = np.arange(e, e + B)  # candidate ends
            emax = E[-1]
            k = np.arange(s + 1, emax)  # interior frames of the longest candidate
            U = (k[None, :] - s) / (E[:, None] - s)
            mask = k[None, :] < E[:, None]
            qa = np.broadcast_to(q[s], U.shape + (4,))
            qb = np.broadcast_to(q[E][:, None, :], U.shape + (4,))
            err = angle(slerp(qa, qb, np.where(mask, U, 0.0)), np.broadcast_to(q[k], U.shape + (4,)))
            bad = np.any((err > tol) & mask, axis=1)
            if bad.any():
                nxt = int(E[np.argmax(bad)]) - 1
                break
            e = emax + 1
            grow = min(grow * 2, 4096)
        if nxt is None:
            nxt = n - 1
        keys.append(nxt)
        s = nxt
    return keys


# ---------------------------------------------------------------------------------------------
# glTF-Transform's resample() rule (keyframe-resample's resample(), JavaScript), in plain Python
# floats (JavaScript numbers are doubles; the accessor values are float32 for the component test)

GLM_EPSILON = 0.000001  # keyframe-resample constants.ts, as gl-matrix's glMatrix.EPSILON
JS_EPSILON = 2.220446049250313e-16  # Number.EPSILON


def _glm_slerp(a, b, t):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    cosom = ax * bx + ay * by + az * bz + aw * bw
    if cosom < 0.0:
        cosom, bx, by, bz, bw = -cosom, -bx, -by, -bz, -bw
    if 1.0 - cosom > GLM_EPSILON:
        omega = math.acos(cosom)
        sinom = math.sin(omega)
        s0 = math.sin((1.0 - t) * omega) / sinom
        s1 = math.sin(t * omega) / sinom
    else:
        s0, s1 = 1.0 - t, t
    return (s0 * ax + s1 * bx, s0 * ay + s1 * by, s0 * az + s1 * bz, s0 * aw + s1 * bw)


def _js_acos(x):
    return math.acos(x) if -1.0 <= x <= 1.0 else float("nan")


def _glm_get_angle(a, b):
    d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
    return _js_acos(2 * d * d - 1)


def _angle1(a, b):
    d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
    s = 1.0 if d >= 0 else -1.0
    c = math.sqrt(sum((a[i] - s * b[i]) ** 2 for i in range(4)))
    return 4 * math.asin(min(1.0, c / 2))


def gltf_resample(q, tol, test):
    """Kept frame indices. q (n,4); test 'angle' (tol in rad) or 'components' (tol per component,
    frames rounded to float32). Frame times are uniform: t = (i - kept) / (i + 1 - kept)."""
    if test == "components":
        vals = [tuple(float(x) for x in r) for r in q.astype(np.float32)]
    else:
        vals = [tuple(float(x) for x in r) for r in q]
    n = len(vals)
    keys = [0]
    last = 0
    for i in range(1, n - 1):
        prev, value, nxt = vals[last], vals[i], vals[i + 1]
        t = (i - last) / (i + 1 - last)
        sample = _glm_slerp(prev, nxt, t)
        ang = _glm_get_angle(prev, value) + _glm_get_angle(value, nxt)
        if test == "components":
            miss = any(abs(value[c] - sample[c]) > tol for c in range(4))
        else:
            miss = _angle1(value, sample) > tol
        if miss or ang + JS_EPSILON >= math.pi:  # NaN compares false, as in JavaScript
            keys.append(i)
            last = i
    if n > 1:
        keys.append(n - 1)
    return keys


# ---------------------------------------------------------------------------------------------
# inbetween


def run_reduce(binary, clip, tol, scheme, method, vel, out, timeout):
    cmd = [binary, "reduce", clip, "--tolerance", repr(tol), "--scheme", scheme, "--method", method,
           "--translation-tolerance", "1e9", "-o", out]
    if not vel:
        cmd.append("--no-velocities")
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, None, time.perf_counter() - t0
    dt = time.perf_counter() - t0
    if p.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{p.stderr}")
    with open(out) as f:
        doc = json.load(f)
    return doc, [len(t["keys"]) for t in doc["tracks"]], dt


def replay(binary, doc, scheme, work, dense, names):
    """Per-track max error (rad) of `inbetween interp` on the keys, at every frame of the clip."""
    for t in doc["tracks"]:
        for k in t["keys"]:
            k.pop("translation", None)
    kj = os.path.join(work, "replay_keys.json")
    with open(kj, "w") as f:
        json.dump(doc, f)
    npy = os.path.join(work, "replay.npy")
    subprocess.run([binary, "interp", kj, "--scheme", scheme, "--output-format", "npy", "-o", npy],
                   check=True)
    a = np.load(npy)
    out = []
    for ti, t in enumerate(doc["tracks"]):
        assert t["name"] == names[ti], (t["name"], names[ti])
        rows = a[a[:, 0] == ti]
        q = dense[ti]
        assert len(rows) == len(q), (t["name"], len(rows), len(q))
        assert np.array_equal(rows[:, 1], np.arange(len(q)))
        out.append(float(angle(rows[:, 3:7], q).max()))
    return out


# ---------------------------------------------------------------------------------------------


def parse_config(c):
    scheme, method, vel = c.split(":")
    assert scheme in ("bezier", "hermite", "slerp", "squad"), c
    assert method in ("greedy", "optimal"), c
    assert vel in ("vel", "novel"), c
    return scheme, method, vel == "vel"


def config_label(c):
    scheme, method, vel = parse_config(c)
    return f"inbetween {scheme} {method}" + ("" if vel else " --no-velocities")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bin", required=True, help="the inbetween binary")
    ap.add_argument("--clip-dir", required=True, help="where fetch_clips.sh put the clips")
    ap.add_argument("--work", default=None, help="scratch directory (default: a temporary one)")
    ap.add_argument("--clips", default=",".join(CLIPS), help="comma-separated clip names")
    ap.add_argument("--seconds", type=float, default=None,
                    help="keep only SECONDS of each clip (from --offset), default the whole clip")
    ap.add_argument("--offset", type=float, default=0.0, help="start of the trim, seconds")
    ap.add_argument("--tolerances", default="0.25,0.5,1,2", help="degrees")
    ap.add_argument("--configs", default=",".join(DEFAULT_CONFIGS),
                    help="scheme:method:vel|novel, comma-separated (e.g. bezier:optimal:vel)")
    ap.add_argument("--methods", default=None,
                    help="keep only the configs with these methods (greedy,optimal)")
    ap.add_argument("--replay", default="all",
                    help="configs to replay through `inbetween interp` (all, none, or a list)")
    ap.add_argument("--timeout", type=float, default=None, help="seconds per reduce run")
    ap.add_argument("--json", default=None, help="write every figure here")
    args = ap.parse_args()

    tols = [float(x) for x in args.tolerances.split(",")]
    configs = args.configs.split(",")
    if args.methods:
        keep = set(args.methods.split(","))
        configs = [c for c in configs if parse_config(c)[1] in keep]
    replay_set = (set(configs) if args.replay == "all" else set()
                  if args.replay == "none" else set(args.replay.split(",")))
    work = args.work or tempfile.mkdtemp(prefix="reduce-compare-")
    os.makedirs(work, exist_ok=True)
    t_start = time.perf_counter()

    results = {"tolerances_deg": tols, "configs": configs, "seconds": args.seconds,
               "offset": args.offset, "clips": {}}
    for clip in args.clips.split(","):
        src = os.path.join(args.clip_dir, clip + ".bvh")
        joints, motion, ft, _ = read_bvh(src)
        fps = 1 / float(ft)
        path = src
        if args.seconds is not None:
            first = int(round(args.offset * fps))
            count = int(round(args.seconds * fps)) + 1
            path = os.path.join(work, f"{clip}_trim.bvh")
            write_trimmed(src, path, first, count)
            joints, motion, ft, _ = read_bvh(path)
        names = [j[0] for j in joints]
        dense = [dense_quats(order, motion[:, cols]) for _, order, cols in joints]
        n = len(motion)
        cr = {"frames": n, "tracks": len(joints), "fps": round(fps, 3), "rules": {}}
        print(f"{clip}: {n} frames at {fps:.3f} fps, {len(joints)} tracks", file=sys.stderr)
        for tol_deg in tols:
            tol = math.radians(tol_deg)
            r = {}
            t0 = time.perf_counter()
            sg = [slerp_greedy(q, tol) for q in dense]
            sg_err = [float(slerp_replay(q, k).max()) for q, k in zip(dense, sg)]
            assert max(sg_err) <= tol * (1 + 1e-9), (clip, tol_deg, max(sg_err))
            r["slerp-greedy"] = {"keys": [len(k) for k in sg], "max_err": sg_err,
                                 "seconds": time.perf_counter() - t0}
            for test, name, ptol in (("angle", "gltf-transform (angle)", tol),
                                     ("components", "gltf-transform (components)", math.sin(tol / 4))):
                t0 = time.perf_counter()
                gk = [gltf_resample(q, ptol, test) for q in dense]
                ge = [float(slerp_replay(q, k).max()) for q, k in zip(dense, gk)]
                r[name] = {"keys": [len(k) for k in gk], "max_err": ge,
                           "seconds": time.perf_counter() - t0}
            for c in configs:
                scheme, method, vel = parse_config(c)
                out = os.path.join(work, "keys.json")
                doc, counts, dt = run_reduce(args.bin, path, tol_deg, scheme, method, vel, out,
                                             args.timeout)
                if doc is None:
                    r[c] = {"timeout": dt}
                    print(f"  {tol_deg}° {c}: timeout after {dt:.1f} s", file=sys.stderr)
                    continue
                assert [t["name"] for t in doc["tracks"]] == names
                entry = {"keys": counts, "seconds": dt}
                if c in replay_set:
                    entry["max_err"] = replay(args.bin, doc, scheme, work, dense, names)
                r[c] = entry
                print(f"  {tol_deg}° {c}: {sum(counts)} keys "
                      f"(slerp-greedy {sum(r['slerp-greedy']['keys'])}), {dt:.2f} s", file=sys.stderr)
            cr["rules"][str(tol_deg)] = r
        results["clips"][clip] = cr
    results["elapsed_seconds"] = time.perf_counter() - t_start
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    print(report(results))


def report(res):
    tols = res["tolerances_deg"]
    clips = res["clips"]
    rules = ["slerp-greedy", "gltf-transform (angle)", "gltf-transform (components)"] + res["configs"]
    lab = lambda r: r if not ":" in r else config_label(r)
    out = []
    frames = sum(c["frames"] for c in clips.values())
    tracks = sum(c["tracks"] for c in clips.values())
    rot = sum(c["frames"] * c["tracks"] for c in clips.values())
    trim = ("whole clips" if res["seconds"] is None
            else f"{res['seconds']:g} s of each clip from {res['offset']:g} s")
    out.append(f"Pooled over {len(clips)} clips ({trim}): {tracks} tracks, {frames} frames, "
               f"{rot} rotations per tolerance. Keys kept as a fraction of slerp-greedy's; "
               "in brackets: the largest error measured at any frame (degrees) and the number of "
               "tracks over the tolerance.\n")
    out.append("| rule | " + " | ".join(f"{t:g}°" for t in tols) + " |")
    out.append("|---|" + "---|" * len(tols))
    for rule in rules:
        cells = []
        for t in tols:
            tot = base = 0
            errs = []
            over = 0
            timeout = False
            for c in clips.values():
                r = c["rules"][str(t)]
                if "timeout" in r[rule]:
                    timeout = True
                    continue
                tot += sum(r[rule]["keys"])
                base += sum(r["slerp-greedy"]["keys"])
                if "max_err" in r[rule]:
                    e = [math.degrees(x) for x in r[rule]["max_err"]]
                    errs += e
                    over += sum(1 for x in e if x > t * (1 + 1e-6))
            if timeout:
                cells.append("timeout")
                continue
            s = f"{tot / base:.3f}" if rule != "slerp-greedy" else f"1 ({tot} keys)"
            if errs:
                s += f" [{max(errs):.3g}°, {over}]"
            cells.append(s)
        out.append(f"| {lab(rule)} | " + " | ".join(cells) + " |")
    out.append("")
    out.append("Per clip (keys kept / slerp-greedy's):\n")
    out.append("| clip | frames | fps | tracks | rule | " + " | ".join(f"{t:g}°" for t in tols) + " |")
    out.append("|---|---|---|---|---|" + "---|" * len(tols))
    for name, c in clips.items():
        for rule in rules:
            cells = []
            for t in tols:
                r = c["rules"][str(t)]
                if "timeout" in r[rule]:
                    cells.append("timeout")
                elif rule == "slerp-greedy":
                    cells.append(f"{sum(r[rule]['keys'])} keys")
                else:
                    cells.append(f"{sum(r[rule]['keys']) / sum(r['slerp-greedy']['keys']):.3f}")
            out.append(f"| {name} | {c['frames']} | {c['fps']:g} | {c['tracks']} | {lab(rule)} | "
                       + " | ".join(cells) + " |")
    out.append("")
    rt = {}
    for c in clips.values():
        for t in tols:
            for rule, v in c["rules"][str(t)].items():
                rt[rule] = rt.get(rule, 0) + v.get("seconds", v.get("timeout", 0))
    out.append("Time spent per rule (s, all clips and tolerances; inbetween: whole reduce "
               "processes): " + ", ".join(f"{lab(k)} {v:.1f}" for k, v in rt.items()))
    out.append(f"Elapsed: {res['elapsed_seconds']:.0f} s")
    return "\n".join(out)


if __name__ == "__main__":
    main()
