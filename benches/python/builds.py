"""Two or more builds of the extension module timed against each other in one process
(docs/performance.md, issue 48).

    python benches/python/builds.py curve|resample A.so B.so [...] [--rounds 25]

Each `.so` is a build of `_inbetween_avx2` (or, with `--module _inbetween`, of the portable
module), loaded side by side under its own name; the cases of `bench.py` run on each build in
turn, `--rounds` times, and the medians are printed with the largest difference of each
build's result from the first's. Alternating in one process keeps the machine's drift (other
jobs, the state of the caches and of the allocator) out of the comparison, which separate
processes run minutes apart do not: on a shared 2-core machine their medians move by a fifth.
"""

import argparse
import importlib.util
import statistics
import sys
import time

from peer import normal_speed

normal_speed()  # before numpy is imported (peer.py says why)

import numpy as np
from bench import curve_case, resample_case


def load(path, module):
    """The extension at `path`, imported as `module` without keeping it in `sys.modules`, so
    that the next build can be imported under the same name."""
    spec = importlib.util.spec_from_file_location(module, path)
    m = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(m)
    sys.modules.pop(module, None)
    return m


def cases():
    """bench.py's two cases, on a build `m`."""
    times, q, t = curve_case()
    clip = resample_case()
    return {
        "curve": lambda m: m.Curve(times, q)(t),
        "resample": lambda m: m.resample(clip, 120, 100),
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case", choices=["curve", "resample"])
    ap.add_argument("builds", nargs="+")
    ap.add_argument("--module", default="_inbetween_avx2")
    ap.add_argument("--rounds", type=int, default=25)
    args = ap.parse_args()
    run = cases()[args.case]
    mods = [load(p, args.module) for p in args.builds]
    took = [[] for _ in mods]
    first = []
    for r in range(args.rounds):
        for i, m in enumerate(mods):
            start = time.perf_counter()
            out = run(m)
            took[i].append(time.perf_counter() - start)
            if r == 0:
                first.append(out)
    for path, t, out in zip(args.builds, took, first):
        print(f"{path}: median {1000 * statistics.median(t):.1f} ms, min {1000 * min(t):.1f} ms, "
              f"largest difference from the first build {np.abs(out - first[0]).max():.1e}")


if __name__ == "__main__":
    main()
