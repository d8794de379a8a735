"""Writes the synthetic BVH clip of the BVH benchmark (issue 14) — deterministic, no randomness:
the same arguments give the same bytes. Called by run.sh; never committed.

    python3 gen_clip.py OUT.bvh [--minutes 10] [--fps 120]

Skeleton: 60 joints, all with rotation channels — Hips (6 channels: positions + ZXY), a spine, neck
and head, two arms with five fingers each (thumbs 3 joints, the others 4), two legs — 183 channels per row. Rotation orders are
mixed the way real exports mix them (ZXY for the body, ZYX for the fingers, YXZ for the legs).
Motion: every channel a sum of two sines with per-channel frequencies (0.05–1.6 Hz) and phases;
the root yaw turns steadily so its angle wraps at ±180° as exporters write it. Numbers are
written with 6 decimals ("%.6f", as many mocap exporters do). Frame Time is the rounded
1/fps ("0.008333" at 120 fps).
"""
import argparse
import math


def skeleton():
    """(name, parent index, offset, channels) in file order (depth first)."""
    body = "Zrotation Xrotation Yrotation"
    finger = "Zrotation Yrotation Xrotation"
    leg = "Yrotation Xrotation Zrotation"
    joints = [("Hips", None, (0.0, 95.0, 0.0),
               "Xposition Yposition Zposition " + body)]

    def add(name, parent, offset, channels):
        joints.append((name, parent, offset, channels))
        return len(joints) - 1

    spine = add("Spine", 0, (0.0, 10.0, 0.0), body)
    spine1 = add("Spine1", spine, (0.0, 12.0, 0.0), body)
    spine2 = add("Spine2", spine1, (0.0, 12.0, 0.0), body)
    neck = add("Neck", spine2, (0.0, 14.0, 0.0), body)
    add("Head", neck, (0.0, 9.0, 1.0), body)
    for side, s in (("Left", 1.0), ("Right", -1.0)):
        sh = add(f"{side}Shoulder", spine2, (s * 4.0, 11.0, 0.0), body)
        arm = add(f"{side}Arm", sh, (s * 13.0, 0.0, 0.0), body)
        fore = add(f"{side}ForeArm", arm, (s * 27.0, 0.0, 0.0), body)
        hand = add(f"{side}Hand", fore, (s * 25.0, 0.0, 0.0), body)
        for k, f in enumerate(("Thumb", "Index", "Middle", "Ring", "Pinky")):
            parent = hand
            for n in range(1, 4 if f == "Thumb" else 5):
                offset = (s * 3.0, 0.0, 2.0 - k) if n == 1 else (s * 2.5, 0.0, 0.0)
                parent = add(f"{side}Hand{f}{n}", parent, offset, finger)
    for side, s in (("Left", 1.0), ("Right", -1.0)):
        up = add(f"{side}UpLeg", 0, (s * 9.0, -6.0, 0.0), leg)
        lo = add(f"{side}Leg", up, (0.0, -42.0, 0.0), leg)
        foot = add(f"{side}Foot", lo, (0.0, -40.0, 0.0), leg)
        add(f"{side}ToeBase", foot, (0.0, -4.0, 12.0), leg)
    return joints


def write_hierarchy(f, joints):
    children = {i: [] for i in range(len(joints))}
    for i, (_, p, _, _) in enumerate(joints):
        if p is not None:
            children[p].append(i)

    def emit(i, depth):
        name, p, off, ch = joints[i]
        pad = "  " * depth
        f.write(f"{pad}{'ROOT' if p is None else 'JOINT'} {name}\n{pad}{{\n")
        f.write(f"{pad}  OFFSET {off[0]:.6f} {off[1]:.6f} {off[2]:.6f}\n")
        f.write(f"{pad}  CHANNELS {len(ch.split())} {ch}\n")
        for c in children[i]:
            emit(c, depth + 1)
        if not children[i]:
            f.write(f"{pad}  End Site\n{pad}  {{\n{pad}    OFFSET 0.000000 3.000000 0.000000\n{pad}  }}\n")
        f.write(f"{pad}}}\n")

    f.write("HIERARCHY\n")
    emit(0, 0)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--minutes", type=float, default=10.0)
    ap.add_argument("--fps", type=int, default=120)
    a = ap.parse_args()
    joints = skeleton()
    assert len(joints) == 60, len(joints)
    order = [c for _, _, _, ch in joints for c in ch.split()]
    n_ch = len(order)
    frames = int(round(a.minutes * 60 * a.fps))
    # Per channel: amplitude, two angular frequencies (rad/s), two phases.
    params = []
    for c, name in enumerate(order):
        if name.endswith("position"):
            amp = (20.0, 3.0, 20.0)["XYZ".index(name[0])]
        else:
            amp = 10.0 + 50.0 * ((c * 0.6180339887) % 1.0)
        w1 = 2 * math.pi * (0.05 + 1.55 * ((c * 0.7548776662) % 1.0))
        w2 = 2 * math.pi * (0.05 + 1.55 * ((c * 0.5698402910) % 1.0))
        params.append((amp, w1, w2, c * 1.3, c * 0.7))
    yaw = order.index("Yrotation")  # the root's yaw: turns 10°/s, wrapped to (-180, 180]
    with open(a.out, "w") as f:
        write_hierarchy(f, joints)
        f.write(f"MOTION\nFrames: {frames}\nFrame Time: {1.0 / a.fps:.6f}\n")
        fmt = " ".join(["%.6f"] * n_ch) + "\n"
        rows = []
        for i in range(frames):
            t = i / a.fps
            v = [amp * (0.7 * math.sin(w1 * t + p1) + 0.3 * math.sin(w2 * t + p2))
                 for amp, w1, w2, p1, p2 in params]
            y = (10.0 * t + v[yaw] + 180.0) % 360.0 - 180.0
            v[yaw] = y
            rows.append(fmt % tuple(v))
            if len(rows) == 1024:
                f.writelines(rows)
                rows.clear()
        f.writelines(rows)


if __name__ == "__main__":
    main()
