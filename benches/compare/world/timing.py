#!/usr/bin/env python3
"""Time of `reduce --position-tolerance LEN` against one per-joint `reduce --tolerance θ
--translation-tolerance τ` at rule (a)'s θ and τ for the same LEN (read from a compare.py
--json), side by side: the two commands interleaved, RUNS times each, medians per clip, then
pooled (sums of the medians). Run by hand, not in CI:

    bash benches/compare/world/run.sh --schemes bezier,slerp --json a.json   # rule (a)
    python3 benches/compare/world/timing.py --bin target/release/inbetween \\
        --clip-dir target/reduce-compare/clips --json a.json \\
        [--lens 0.5,1,2] [--schemes bezier,slerp] [--runs 5]

(the venv of run.sh, target/world-compare/venv, has what it needs; so does any Python 3).
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile
import time


def wall(cmd):
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", required=True)
    ap.add_argument("--clip-dir", required=True)
    ap.add_argument("--json", required=True, help="compare.py --json with rule (a)'s results")
    ap.add_argument("--lens", default="0.5,1,2", help="LEN values, cm")
    ap.add_argument("--schemes", default="bezier")
    ap.add_argument("--runs", type=int, default=5)
    args = ap.parse_args()
    doc = json.load(open(args.json))
    out = os.path.join(tempfile.mkdtemp(prefix="world-timing-"), "keys.json")
    pooled = {}
    for clip, c in doc["clips"].items():
        path = os.path.join(args.clip_dir, clip + ".bvh")
        cm = c["cm_per_unit"]
        for lcm in args.lens.split(","):
            L = float(lcm) / cm
            for s in args.schemes.split(","):
                a = c["len"][repr(float(lcm))][f"a:{s}"]
                tau = a["tau_fraction"] * L
                per_joint = [args.bin, "reduce", path, "--tolerance", repr(a["theta_deg"]),
                             "--translation-tolerance", repr(tau), "--scheme", s, "-o", out]
                world = [args.bin, "reduce", path, "--position-tolerance", repr(L),
                         "--scheme", s, "-o", out]
                pj, pt = [], []
                for _ in range(args.runs):
                    pj.append(wall(per_joint))
                    pt.append(wall(world))
                m = (statistics.median(pj), statistics.median(pt))
                key = (lcm, s)
                acc = pooled.setdefault(key, [0.0, 0.0])
                acc[0] += m[0]
                acc[1] += m[1]
                print(f"{clip} {lcm} cm {s}: per-joint {m[0]:.3f} s, position-tolerance "
                      f"{m[1]:.3f} s ({m[1] / m[0]:.2f}x)", flush=True)
    for (lcm, s), (a, b) in pooled.items():
        print(f"pooled {lcm} cm {s}: per-joint {a:.2f} s, position-tolerance {b:.2f} s: "
              f"{b / a:.2f}x")


if __name__ == "__main__":
    main()
