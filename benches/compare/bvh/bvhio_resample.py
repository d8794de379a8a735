"""The Python side of the BVH benchmark (issue 14): bvhio 1.5.4 reads a BVH clip, resamples it
to half its rate, and writes a BVH.

    python bvhio_resample.py IN.bvh OUT.bvh

bvhio has no resampling by time: its only interpolation is `Joint.getKeyframe(frame)` at integer
frame ids of its hierarchy structure (its README's "Interpolate between keyframes" scales the
ids), which cannot express 120 -> 60 fps other than by keeping every other id. So this keeps
every other frame, the cheapest thing a bvhio user can do, on bvhio's lighter structure
(`readAsBvh` -> `BvhJoint.Keyframes`, its own parse into per-joint poses) rather than the joint
hierarchy (`readAsHierarchy`/`writeHierarchy`, which also converts every key to and from rest-pose
space). That is less work than inbetween's resampling (no interpolation at all), so the
comparison favours bvhio. `writeBvh` writes each joint's rotation back as Euler angles in the
joint's channel order (precision 9 digits after the point, its default).
"""
import sys

import bvhio


def main(src, dst):
    bvh = bvhio.readAsBvh(src)
    for joint, _, _ in bvh.Root.layout():
        joint.Keyframes = joint.Keyframes[::2]
    bvh.FrameCount = len(bvh.Root.Keyframes)
    bvh.FrameTime = bvh.FrameTime * 2
    bvhio.writeBvh(dst, bvh)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
