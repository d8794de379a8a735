"""`inbetween.read` of a BVH clip against bvhio (docs/performance.md, issue 25).

    python benches/python/bench_read.py CLIP.bvh [--repeat 3]

Both read the file into per-joint rotations in this one process, alternately, `--repeat`
times; prints the medians and their ratio. bvhio (pure Python, pinned in
fixtures/requirements.txt) must be importable beside the installed `inbetween`.
"""

import argparse
import statistics
import time

from peer import describe, normal_speed

normal_speed()  # before numpy is imported (peer.py says why)

import bvhio
import numpy as np

import inbetween


def with_bvhio(path):
    root = bvhio.readAsHierarchy(path)
    joints = root.layout()
    frames = len(root.Keyframes)
    # Every joint's local rotation at every frame, as quaternion arrays (w, x, y, z).
    out = np.empty((frames, len(joints), 4))
    for j, (joint, _, _) in enumerate(joints):
        for k, (_, pose) in enumerate(joint.Keyframes):
            r = pose.Rotation
            out[k, j] = (r.w, r.x, r.y, r.z)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("clip")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    print(describe())
    ours, theirs = [], []
    for _ in range(a.repeat):
        t = time.perf_counter()
        clip = inbetween.read(a.clip)
        ours.append(time.perf_counter() - t)
        t = time.perf_counter()
        q = with_bvhio(a.clip)
        theirs.append(time.perf_counter() - t)
    mo, mt = statistics.median(ours), statistics.median(theirs)
    print(f"read {a.clip}: {clip.rotations.shape} inbetween {mo:.3f} s, bvhio {mt:.3f} s "
          f"({q.shape}), ratio {mt / mo:.1f}x (medians of {a.repeat})")


if __name__ == "__main__":
    main()
