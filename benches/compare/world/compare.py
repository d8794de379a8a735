"""Keys kept by `inbetween reduce --position-tolerance LEN` on real motion capture, against the
per-joint `--tolerance θ` at the largest uniform θ that meets LEN in world space, and against
ozz-animation's optimizer rule (its real world error measured). Called by run.sh (see there);
the figures are written to results.md next to this file.

Clips: the eight public BVH clips of benches/compare/reduce (fetch_clips.sh, never committed),
on which the rule's constants were chosen; with `--set held-out`, eighteen clips held out from
its design (fetch_held_out.sh: MASS's eight, in cm, and ten of Xia et al.'s on the CMU skeleton,
in the CMU unit below; the k^0.7 start of f4f3a67 was compared on them too). The world points are every joint's origin and End Site and, where a joint's
rotation moves neither, its default end points (docs/spec.md §4.7; bvh.add_default_ends),
composed from the root (docs/spec.md §4.8; bvh.py here for the independent measure).

Units. BVH has none; LEN is given in cm and converted per clip to its own units (UNITS below):

- 01_01, 01_03 (CMU, cgspeed BVH conversion): the cgspeed files keep the ASF's lengths. CMU's
  FAQ (mocap.cs.cmu.edu/faqs.php) gives ASF lengths × (1/0.45)·2.54/100 = 0.056444 m, so one
  unit is 5.6444 cm. The data agree: at rest the figure spans 25.65 units from toe End Site to
  head End Site (1.45 m at 5.64 cm, feet and head ends being inside the body's outline), and
  the femur (LeftLeg's OFFSET) is 7.16 units = 40.4 cm; read as cm the figure would be 26 cm
  tall, as inches 65 cm.
- Boxing_Toes (173 units tall at rest), test and test2 (thigh + shin 43.5 + 42.4 = 86 units;
  about 155 units tall standing), test_mocapbank (167), test_freebvh (Mixamo, 178): cm.
- test3 (Blender/Rigify names; pelvis at 0.718, 1.33–1.36 units tall): metres, 100 cm a unit.

Rules, per clip and LEN ∈ {0.5, 1, 2} cm (L = LEN in the clip's units):

- (a) per-joint: `inbetween reduce CLIP --tolerance θ --translation-tolerance τ --scheme S -o
  keys.json`, θ the largest uniform angle found by bisection on log θ for which `inbetween diff
  CLIP keys.json --scheme S --max-position L` exits 0 (every joint origin and End Site within L
  of the capture at every frame, and every translation within L). Bracket: θ₀ = (L − τ)/R
  radians, R the largest sum, over a point, of its distances to the joints whose rotation moves
  it (frame 0): a first-order bound that passes; then ×4 until a θ fails; then halving the
  log-interval; 12 runs of reduce+diff in all per τ. τ (the position channels' tolerance: the
  roots, and test3's spine and neck) is τ = f·L for each f in --tau-fractions (default 0.1,
  0.25, 0.5), and the f with the fewest keys is kept: the root's error adds to every point, so
  τ trades root keys against the angle left for every joint; taking the best of three is in
  (a)'s favour.
- position-tolerance: `inbetween reduce CLIP --position-tolerance L --scheme S -o keys.json`
  (skipped, with a message, when the binary has no such option), then `inbetween diff ... --max-
  position L`: its keys and its largest world displacement.
- ozz: ozz-animation's AnimationOptimizer rule (ozz.py: source, commit, simplifications) with
  tolerance L, at distance 0 (the points measured are the joints and End Sites) and at its
  default distance (10 cm, in the clip's units); its keys replayed as it plays them (NLerp,
  lerp, ends held) and composed here, the real largest displacement reported: it is not bound.
  "ozz fitted": the same rule at distance 0 with the largest tolerance (bisection on log
  tolerance, --steps runs) whose real error is within L: ozz at the same world bound as (a)
  (something ozz itself cannot know without this replay).
- Every inbetween result kept in the tables is also measured independently: `inbetween interp
  keys.json --skeleton CLIP --scheme S -o out.bvh`, then both BVH composed by bvh.py (scipy
  Euler, numpy FK) and compared point by point at every frame ("indep." in the JSON; the table
  shows diff's figure and the largest disagreement between the two).

Keys counted: the sum over tracks of the keys in keys.json (one key per track and kept frame,
carrying the rotation and, where the joint has position channels, the translation); for ozz
the union of a joint's rotation and translation key frames (ozz.py). Ratios pooled: sums over
every track of every clip.
"""
import argparse
import datetime
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bvh  # noqa: E402
import ozz  # noqa: E402

CLIPS = ["01_01", "01_03", "Boxing_Toes", "test", "test2", "test3", "test_mocapbank", "test_freebvh"]
# Held out from the rule's design (fetch_held_out.sh; `--set held-out`).
HELD_OUT = ["mass_backflip", "mass_balance", "mass_cart", "mass_dance", "mass_kick",
            "mass_pirouette", "mass_run", "mass_walk", "xia_angry_13_000", "xia_depressed_13_000",
            "xia_depressed_18_000", "xia_example", "xia_neutral_01_000", "xia_neutral_16_000",
            "xia_old_13_000", "xia_sexy_01_000", "xia_sexy_01_001", "xia_strutting_01_000"]
UNITS = {  # cm per length unit of the clip (see the module docstring)
    "01_01": 2.54 / 0.45, "01_03": 2.54 / 0.45, "Boxing_Toes": 1.0, "test": 1.0, "test2": 1.0,
    "test3": 100.0, "test_mocapbank": 1.0, "test_freebvh": 1.0,
    **{c: (1.0 if c.startswith("mass_") else 2.54 / 0.45) for c in HELD_OUT},
}


def run(cmd, timeout=None):
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    return p, time.perf_counter() - t0


def count_keys(path):
    with open(path) as f:
        doc = json.load(f)
    return [len(t["keys"]) for t in doc["tracks"]]


class Inbetween:
    def __init__(self, binary, work, timeout):
        self.bin, self.work, self.timeout = binary, work, timeout
        self.runs = 0
        self.seconds = 0.0
        h = subprocess.run([binary, "reduce", "--help"], capture_output=True, text=True).stdout
        self.has_position_tolerance = "--position-tolerance" in h

    def reduce(self, clip, args, scheme):
        out = os.path.join(self.work, "keys.json")
        cmd = [self.bin, "reduce", clip, *args, "--scheme", scheme, "-o", out]
        p, dt = run(cmd, self.timeout)
        self.runs += 1
        self.seconds += dt
        if p.returncode != 0:
            sys.exit(f"failed: {' '.join(cmd)}\n{p.stderr}")
        return out, dt

    def diff(self, clip, keys, scheme, L):
        dj = os.path.join(self.work, "diff.json")
        cmd = [self.bin, "diff", clip, keys, "--scheme", scheme, "--output-format", "json",
               "--max-position", repr(L), "-o", dj]
        p, dt = run(cmd, self.timeout)
        self.seconds += dt
        if p.returncode not in (0, 1):
            sys.exit(f"failed: {' '.join(cmd)}\n{p.stderr}")
        with open(dj) as f:
            tot = json.load(f)["total"]
        return p.returncode == 0, tot["max_world"], tot.get("max_translation")

    def independent(self, clip_path, clip, ref, keys, scheme):
        """Largest displacement, by bvh.py, of `interp keys --skeleton CLIP` from the capture."""
        ob = os.path.join(self.work, "replay.bvh")
        p, dt = run([self.bin, "interp", keys, "--skeleton", clip_path, "--scheme", scheme,
                     "-o", ob], self.timeout)
        if p.returncode != 0:
            sys.exit(f"interp failed\n{p.stderr}")
        b = bvh.read_bvh(ob)
        bvh.add_default_ends(b)
        assert b.frames == clip.frames, (b.frames, clip.frames)
        pb = bvh.world_points(b, bvh.local_rotations(b), bvh.local_translations(b))
        return float(np.linalg.norm(pb - ref, axis=-1).max())


def lever_sum(clip, ref):
    """R: per point, the sum of its distances (frame 0) to the joint origins whose rotation moves
    it (strict ancestors for an origin; the joint itself too for an End Site); the largest."""
    rot = {ji for ji, j in enumerate(clip.joints) if j.rot_cols}
    p0 = ref[0]
    idx, k = [], 0
    for j in clip.joints:
        idx.append(k)
        k += 1 + len(j.end_sites)
    best = 0.0
    for ji, j in enumerate(clip.joints):
        anc, a = [], j.parent
        while a >= 0:
            anc.append(a)
            a = clip.joints[a].parent
        pts = [(idx[ji], anc)] + [(idx[ji] + 1 + e, anc + [ji]) for e in range(len(j.end_sites))]
        for pi, movers in pts:
            s = sum(float(np.linalg.norm(p0[pi] - p0[idx[m]])) for m in movers if m in rot)
            best = max(best, s)
    return best


def bisect_theta(ib, path, scheme, L, tau, R, steps):
    """Largest θ (degrees) found whose keys pass diff --max-position L. Probes listed."""
    probes = []

    def probe(theta):
        keys, dt = ib.reduce(path, ["--tolerance", repr(theta), "--translation-tolerance",
                                    repr(tau)], scheme)
        ok, world, trans = ib.diff(path, keys, scheme, L)
        probes.append({"theta": theta, "ok": ok, "keys": sum(count_keys(keys)), "max_world": world,
                       "max_translation": trans, "seconds": dt})
        return ok

    theta = max(math.degrees((L - tau) / R), 1e-6)
    while not probe(theta) and len(probes) < steps:
        theta /= 4  # the first-order bound missed (it should not): go down
    lo = theta if probes[-1]["ok"] else None
    hi = None
    if lo is not None:
        t = lo
        while len(probes) < steps:
            t = min(t * 4, 180.0)
            if not probe(t):
                hi = t
                break
            lo = t
            if t >= 180.0:
                break
        while hi is not None and len(probes) < steps:
            mid = math.sqrt(lo * hi)
            if probe(mid):
                lo = mid
            else:
                hi = mid
    best = max((p for p in probes if p["ok"]), key=lambda p: p["theta"], default=None)
    return best, probes


def bisect_ozz(clip, rot, trans, ref, L, steps):
    """ozz's rule (distance 0) with the largest tolerance found by bisection on log tolerance
    whose real world error is within L: ozz at the same world bound as (a)."""
    probes = []

    def probe(tol):
        kept, _ = ozz.optimize(clip, rot, trans, tol, 0.0)
        err = ozz.world_error(clip, ref, rot, trans, kept)[0]
        probes.append({"tol": tol, "ok": err <= L, "keys": ozz.key_count(kept), "err": err})
        return err <= L

    t = L / 4
    while not probe(t) and len(probes) < steps:
        t /= 2
    lo, hi = (t if probes[-1]["ok"] else None), None
    if lo is not None:
        while len(probes) < steps:
            t = t * 2
            if not probe(t):
                hi = t
                break
            lo = t
        while hi is not None and len(probes) < steps:
            mid = math.sqrt(lo * hi)
            if probe(mid):
                lo = mid
            else:
                hi = mid
    best = max((p for p in probes if p["ok"]), key=lambda p: p["tol"])
    return best, probes


def rule_a(ib, path, clip, ref, s, L, lever, fracs, steps, LEN, cpu):
    """Rule (a): the largest uniform θ (best of the τ fractions) meeting L."""
    t0 = time.perf_counter()
    cands = []
    for f in fracs:
        best, probes = bisect_theta(ib, path, s, L, f * L, lever, steps)
        cands.append({"f": f, "best": best, "probes": probes})
    ok = [c for c in cands if c["best"] is not None]
    pick = min(ok, key=lambda c: c["best"]["keys"]) if ok else None
    entry = {"candidates": cands, "seconds": time.perf_counter() - t0}
    if pick:
        b = pick["best"]
        keys, _ = ib.reduce(path, ["--tolerance", repr(b["theta"]),
                                   "--translation-tolerance", repr(pick["f"] * L)], s)
        counts = count_keys(keys)
        assert sum(counts) == b["keys"]
        entry.update({"theta_deg": b["theta"], "tau_fraction": pick["f"],
                      "keys": counts, "max_world": b["max_world"],
                      "indep": ib.independent(path, clip, ref, keys, s)})
        print(f"  {LEN:g} cm {s} (a): θ {b['theta']:.4g}°, τ {pick['f']:g}·L, "
              f"{sum(counts)} keys, world {b['max_world'] * cpu:.4g} cm "
              f"({entry['seconds']:.1f} s)", file=sys.stderr)
    return entry


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bin", required=True, help="the inbetween binary (release build)")
    ap.add_argument("--clip-dir", required=True, help="where fetch_clips.sh put the clips")
    ap.add_argument("--work", default=None, help="scratch directory (default: a temporary one)")
    ap.add_argument("--set", choices=["tuned", "held-out"], default="tuned",
                    help="the clips: the eight of fetch_clips.sh, or the eighteen held out")
    ap.add_argument("--clips", default=None, help="comma-separated clip names (default: --set's)")
    ap.add_argument("--units", default="",
                    help="cm per length unit of clips not in UNITS: name=cm,name=cm")
    ap.add_argument("--lens", default="0.5,1,2", help="LEN values, cm")
    ap.add_argument("--schemes", default="bezier", help="schemes of the inbetween rows (bezier,slerp)")
    ap.add_argument("--tau-fractions", default="0.1,0.25,0.5",
                    help="(a): τ = f·LEN for each f; the one with the fewest keys is kept")
    ap.add_argument("--steps", type=int, default=12, help="(a): reduce+diff runs per bisection")
    ap.add_argument("--ozz-distances", default="0,10", help="ozz `distance` settings, cm")
    ap.add_argument("--ozz-bisect", type=int, default=1,
                    help="1: also ozz (distance 0) at the largest tolerance meeting LEN (0: off)")
    ap.add_argument("--timeout", type=float, default=600, help="seconds per inbetween process")
    ap.add_argument("--json", default=None, help="write every figure here")
    ap.add_argument("--reuse-a", default=None,
                    help="take rule (a)'s results from this --json of an earlier run (same clips, "
                         "LENs and schemes; (a) does not depend on --position-tolerance's rule)")
    ap.add_argument("--out", default=None,
                    help="markdown report (default: results.md, or results-held-out.md)")
    ap.add_argument("--command", default=None, help="the command line to print in the report")
    args = ap.parse_args()
    if args.out is None:
        name = "results.md" if args.set == "tuned" else "results-held-out.md"
        args.out = os.path.join(os.path.dirname(os.path.abspath(__file__)), name)

    if args.clips is None:
        args.clips = ",".join(CLIPS if args.set == "tuned" else HELD_OUT)
    lens = [float(x) for x in args.lens.split(",")]
    schemes = args.schemes.split(",")
    fracs = [float(x) for x in args.tau_fractions.split(",")]
    odists = [float(x) for x in args.ozz_distances.split(",") if x]
    units = dict(UNITS)
    units.update({k: float(v) for k, v in (kv.split("=") for kv in args.units.split(",") if kv)})
    work = args.work or tempfile.mkdtemp(prefix="world-compare-")
    os.makedirs(work, exist_ok=True)
    reused = None
    if args.reuse_a:
        with open(args.reuse_a) as f:
            reused = json.load(f)
    ib = Inbetween(args.bin, work, args.timeout)
    if not ib.has_position_tolerance:
        print("NOTE: this inbetween has no `reduce --position-tolerance` yet: its rows are "
              "skipped (rebuild from a commit that has it).", file=sys.stderr)
    t_start = time.perf_counter()
    res = {"lens_cm": lens, "schemes": schemes, "tau_fractions": fracs, "steps": args.steps,
           "ozz_distances_cm": odists, "ozz_bisect": bool(args.ozz_bisect),
           "has_position_tolerance": ib.has_position_tolerance,
           "clips": {}}
    for name in args.clips.split(","):
        path = os.path.join(args.clip_dir, name + ".bvh")
        clip = bvh.read_bvh(path)
        bvh.add_default_ends(clip)
        cpu = units[name]
        R_, T_ = bvh.local_rotations(clip), bvh.local_translations(clip)
        ref = bvh.world_points(clip, R_, T_)
        lever = lever_sum(clip, ref)
        cr = {"frames": clip.frames, "tracks": len(clip.tracks), "cm_per_unit": cpu,
              "points": ref.shape[1], "lever_units": lever, "len": {}}
        print(f"{name}: {clip.frames} frames, {len(clip.tracks)} tracks, {ref.shape[1]} points, "
              f"{cpu:g} cm a unit", file=sys.stderr)
        for LEN in lens:
            L = LEN / cpu
            r = {}
            for s in schemes:
                # (a)
                if reused is not None:
                    r[f"a:{s}"] = reused["clips"][name]["len"][str(LEN)][f"a:{s}"]
                else:
                    r[f"a:{s}"] = rule_a(ib, path, clip, ref, s, L, lever, fracs, args.steps, LEN,
                                         cpu)
                # position tolerance
                if ib.has_position_tolerance:
                    keys, dt = ib.reduce(path, ["--position-tolerance", repr(L)], s)
                    counts = count_keys(keys)
                    okp, world, trans = ib.diff(path, keys, s, L)
                    r[f"pt:{s}"] = {"keys": counts, "max_world": world, "max_translation": trans,
                                    "within": okp, "seconds": dt,
                                    "indep": ib.independent(path, clip, ref, keys, s)}
                    a = r[f"a:{s}"]
                    a_keys = sum(a["keys"]) if "keys" in a else float("nan")
                    print(f"  {LEN:g} cm {s} position-tolerance: {sum(counts)} keys "
                          f"({sum(counts) / a_keys:.3f} of (a)), world {world * cpu:.4g} cm, "
                          f"{dt:.2f} s", file=sys.stderr)
            for d in odists:
                t0 = time.perf_counter()
                kept, _ = ozz.optimize(clip, R_, T_, L, d / cpu)
                err, fr, pt = ozz.world_error(clip, ref, R_, T_, kept)
                rk = sum(len(k["rot"]) for k in kept.values() if k["rot"] is not None)
                tk = sum(len(k["pos"]) for k in kept.values() if k["pos"] is not None)
                r[f"ozz:{d:g}"] = {"keys": ozz.key_count(kept), "rot_keys": rk, "pos_keys": tk,
                                   "max_world": err, "frame": fr, "point": pt,
                                   "seconds": time.perf_counter() - t0}
                print(f"  {LEN:g} cm ozz distance {d:g} cm: {sum(ozz.key_count(kept))} keys, "
                      f"real world error {err * cpu:.4g} cm ({pt}, frame {fr})", file=sys.stderr)
            if args.ozz_bisect:
                t0 = time.perf_counter()
                best, probes = bisect_ozz(clip, R_, T_, ref, L, args.steps)
                r["ozz:fit"] = {"keys": best["keys"], "tolerance": best["tol"],
                                "tolerance_ratio": best["tol"] / L, "max_world": best["err"],
                                "probes": [{k: v for k, v in q.items() if k != "keys"}
                                           for q in probes],
                                "seconds": time.perf_counter() - t0}
                print(f"  {LEN:g} cm ozz fitted: tolerance {best['tol'] / L:.3g}·L, "
                      f"{sum(best['keys'])} keys, real world error {best['err'] * cpu:.4g} cm",
                      file=sys.stderr)
            cr["len"][str(LEN)] = r
        res["clips"][name] = cr
    res["elapsed_seconds"] = time.perf_counter() - t_start
    res["inbetween_runs"] = ib.runs
    res["inbetween_seconds"] = ib.seconds
    res["meta"] = meta(args)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(res, f, indent=1)
    text = report(res)
    with open(args.out, "w") as f:
        f.write(text + "\n")
    print(text)


def meta(args):
    root = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../.."))

    def git(*a):
        try:
            return subprocess.run(["git", "-C", root, *a], capture_output=True, text=True).stdout.strip()
        except OSError:
            return ""

    ver = subprocess.run([args.bin, "--version"], capture_output=True, text=True).stdout.strip()
    import scipy
    return {"commit": git("rev-parse", "--short", "HEAD"),
            "dirty": bool(git("status", "--porcelain", "--untracked-files=no")),
            "subject": git("log", "-1", "--format=%s")[:100], "version": ver,
            "date": datetime.date.today().isoformat(), "python": platform.python_version(),
            "numpy": np.__version__, "scipy": scipy.__version__,
            "command": args.command or " ".join([os.path.basename(sys.argv[0])] + sys.argv[1:])}


def rule_rows(res):
    rows = []
    for s in res["schemes"]:
        rows.append((f"a:{s}", f"(a) per-joint `--tolerance θ`, θ bisected ({s})"))
        if res["has_position_tolerance"]:
            rows.append((f"pt:{s}", f"`--position-tolerance LEN` ({s})"))
    for d in res["ozz_distances_cm"]:
        lab = "ozz rule, distance 0" if d == 0 else f"ozz rule, distance {d:g} cm"
        rows.append((f"ozz:{d:g}", lab + (" (its default)" if d == 10 else "")
                     + ", tolerance LEN"))
    if res.get("ozz_bisect"):
        rows.append(("ozz:fit", "ozz rule, distance 0, tolerance bisected to meet LEN"))
    return rows


def report(res):
    lens = res["lens_cm"]
    clips = res["clips"]
    m = res["meta"]
    out = []
    frames = sum(c["frames"] for c in clips.values())
    tracks = sum(c["tracks"] for c in clips.values())
    out.append("# World-space bound: keys kept on real motion capture\n")
    out.append(f"Measured {m['date']} on commit {m['commit']}{' (uncommitted changes)' if m['dirty'] else ''} "
               f"({m['version']}, release build), Python {m['python']}, numpy {m['numpy']}, "
               f"scipy {m['scipy']}. Command:\n\n```\n{m['command']}\n```\n")
    out.append(f"Pooled over {len(clips)} clips ({', '.join(clips)}): {tracks} tracks, {frames} "
               "frames. Keys kept (sum over tracks), as a fraction of (a)'s with the same scheme "
               "(ozz: of the first scheme's (a)); in brackets the largest world displacement of "
               "any joint or End Site at any frame, cm, and the clips over LEN. Rules: "
               "benches/compare/world/compare.py.\n")
    if not res["has_position_tolerance"]:
        out.append("**`--position-tolerance` rows skipped: the measured binary has no such "
                   "option.**\n")
    rows = rule_rows(res)
    out.append("| rule | " + " | ".join(f"LEN {x:g} cm" for x in lens) + " |")
    out.append("|---|" + "---|" * len(lens))
    first = res["schemes"][0]
    for key, lab in rows:
        base_key = f"a:{key.split(':')[1]}" if key.startswith(("a:", "pt:")) else f"a:{first}"
        cells = []
        for LEN in lens:
            tot = base = 0
            worst = 0.0
            over = 0
            missing = False
            for c in clips.values():
                r = c["len"][str(LEN)]
                if key not in r or "keys" not in r[key] or "keys" not in r.get(base_key, {}):
                    missing = True
                    continue
                tot += sum(r[key]["keys"])
                base += sum(r[base_key]["keys"])
                w = r[key]["max_world"] * c["cm_per_unit"]
                worst = max(worst, w)
                over += w > LEN * (1 + 1e-9)
            if missing and tot == 0:
                cells.append("–")
                continue
            s = f"{tot} keys" if key == base_key else f"{tot / base:.3f} ({tot} keys)"
            cells.append(s + f" [{worst:.3g} cm, {over}]" + (" (incomplete)" if missing else ""))
        out.append(f"| {lab} | " + " | ".join(cells) + " |")
    out.append("")
    # per clip
    out.append("Per clip: keys (ratio to (a)) [largest world displacement, cm]; (a) also θ and "
               "τ/LEN.\n")
    out.append("| clip | frames | tracks | cm/unit | rule | " + " | ".join(f"{x:g} cm" for x in lens) + " |")
    out.append("|---|---|---|---|---|" + "---|" * len(lens))
    for name, c in clips.items():
        for key, lab in rows:
            base_key = f"a:{key.split(':')[1]}" if key.startswith(("a:", "pt:")) else f"a:{first}"
            cells = []
            for LEN in lens:
                r = c["len"][str(LEN)]
                e = r.get(key, {})
                if "keys" not in e:
                    cells.append("–")
                    continue
                k = sum(e["keys"])
                w = e["max_world"] * c["cm_per_unit"]
                if key.startswith("a:"):
                    cells.append(f"{k} (θ {e['theta_deg']:.3g}°, τ {e['tau_fraction']:g}) [{w:.3g}]")
                elif key == "ozz:fit":
                    b = sum(r[base_key]["keys"])
                    cells.append(f"{k} ({k / b:.3f}; tol {e['tolerance_ratio']:.2g}·LEN) [{w:.3g}]")
                else:
                    b = sum(r[base_key]["keys"]) if "keys" in r.get(base_key, {}) else float("nan")
                    cells.append(f"{k} ({k / b:.3f}) [{w:.3g}]")
            short = lab.split(" (")[0] if key.startswith("a:") else lab
            out.append(f"| {name} | {c['frames']} | {c['tracks']} | {c['cm_per_unit']:.4g} | "
                       f"{short} | " + " | ".join(cells) + " |")
    out.append("")
    # checks
    dis = 0.0
    for c in clips.values():
        for r in c["len"].values():
            for k, e in r.items():
                if "indep" in e:
                    dis = max(dis, abs(e["indep"] - e["max_world"]) * c["cm_per_unit"])
    out.append(f"Independent check: every inbetween result above replayed by `inbetween interp "
               f"--skeleton` and composed by bvh.py agrees with `inbetween diff`'s largest world "
               f"displacement within {dis:.2g} cm.")
    out.append(f"Elapsed: {res['elapsed_seconds']:.0f} s ({res['inbetween_runs']} reduce runs; "
               f"inbetween processes {res['inbetween_seconds']:.0f} s).")
    return "\n".join(out)


if __name__ == "__main__":
    main()
