"""BVH reading and forward kinematics for benches/compare/world (numpy float64, scipy rotations).

Written for this comparison, apart from inbetween's reader; the convention is the one of
docs/spec.md §3 BVH and §4.8 (and of fixtures/world/world_ref.py, which checks it against bvhio):

- a joint's local rotation R is its rotation channels in the listed order, intrinsic, degrees
  (`Zrotation Xrotation Yrotation` is Rz·Rx·Ry: scipy `from_euler("ZXY", ...)`, upper case =
  intrinsic); a joint with one or two rotation channels has the product of those;
- its local translation t is its position channels where it has any (they REPLACE the OFFSET;
  an axis without a position channel is 0), else its OFFSET;
- W_joint = W_parent · T(t) · R (a root's parent is the identity);
- the points of a joint: its origin W_joint·0 and its End Site W_joint·offset (if any).
"""
import numpy as np
from scipy.spatial.transform import Rotation


class Joint:
    def __init__(self, name, parent):
        self.name = name
        self.parent = parent  # index into the joint list, -1 for a root
        self.offset = np.zeros(3)
        self.channels = []  # e.g. ["Xposition", ..., "Zrotation"]
        self.first_col = 0
        self.end_sites = []  # offsets of End Sites (normally 0 or 1)

    @property
    def rot_cols(self):
        return [self.first_col + i for i, c in enumerate(self.channels)
                if c.lower().endswith("rotation")]

    @property
    def rot_order(self):
        return "".join(c[0].upper() for c in self.channels if c.lower().endswith("rotation"))

    @property
    def pos_cols(self):
        """{axis index: column} of the position channels."""
        return {"xyz".index(c[0].lower()): self.first_col + i
                for i, c in enumerate(self.channels) if c.lower().endswith("position")}


class Clip:
    def __init__(self, joints, motion, frame_time):
        self.joints = joints
        self.motion = motion  # (frames, columns)
        self.frame_time = frame_time  # as written (a string)

    @property
    def frames(self):
        return len(self.motion)

    @property
    def tracks(self):
        """Indices of the joints with channels: inbetween's tracks, in file order."""
        return [i for i, j in enumerate(self.joints) if j.channels]

    def children(self, i):
        return [k for k, j in enumerate(self.joints) if j.parent == i]


def read_bvh(path):
    with open(path) as f:
        tok_lines = [l.split() for l in f.read().splitlines()]
    joints, stack, col = [], [], 0
    i = 0
    pending_end = False
    while True:
        t = tok_lines[i]
        i += 1
        if not t:
            continue
        k = t[0].upper()
        if k == "HIERARCHY":
            continue
        if k == "MOTION":
            break
        if k in ("ROOT", "JOINT"):
            parent = stack[-1] if stack else -1
            joints.append(Joint(" ".join(t[1:]), parent))
            stack.append(len(joints) - 1)
            pending_end = False
        elif k == "END":
            pending_end = True
            stack.append("end")
        elif k == "{":
            pass
        elif k == "}":
            stack.pop()
        elif k == "OFFSET":
            v = np.array([float(x) for x in t[1:4]])
            if stack[-1] == "end":
                joints[stack[-2]].end_sites.append(v)
            else:
                joints[stack[-1]].offset = v
        elif k == "CHANNELS":
            j = joints[stack[-1]]
            n = int(t[1])
            j.channels = t[2 : 2 + n]
            j.first_col = col
            col += n
    rows, frame_time = [], None
    for t in tok_lines[i:]:
        if not t:
            continue
        if t[0].startswith("Frames"):
            continue
        if t[0] == "Frame" and t[1].startswith("Time"):
            frame_time = t[-1]
            continue
        rows.append([float(x) for x in t])
    motion = np.array(rows)
    assert motion.shape[1] == col, (path, motion.shape, col)
    return Clip(joints, motion, frame_time)


def local_rotations(clip):
    """{joint index: (frames, 4) quaternions w,x,y,z} for the joints with rotation channels
    (signs continuous along each track)."""
    out = {}
    for ji, j in enumerate(clip.joints):
        cols = j.rot_cols
        if not cols:
            continue
        xyzw = Rotation.from_euler(j.rot_order, clip.motion[:, cols], degrees=True).as_quat()
        q = xyzw[:, [3, 0, 1, 2]]
        d = np.sum(q[1:] * q[:-1], axis=1)
        flip = np.cumsum(np.concatenate([[0], (d < 0).astype(int)])) % 2
        q[flip == 1] *= -1
        out[ji] = q
    return out


def local_translations(clip):
    """{joint index: (frames, 3)} for the joints with position channels."""
    out = {}
    for ji, j in enumerate(clip.joints):
        pc = j.pos_cols
        if not pc:
            continue
        t = np.zeros((clip.frames, 3))
        for axis, c in pc.items():
            t[:, axis] = clip.motion[:, c]
        out[ji] = t
    return out


def quat_to_matrix(q):
    """(n, 4) w,x,y,z (normalised here) -> (n, 3, 3)."""
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    return Rotation.from_quat(q[:, [1, 2, 3, 0]]).as_matrix()


def add_default_ends(clip):
    """docs/spec.md §4.7, "Every bone is bounded": a joint with rotation channels whose rotation
    would move no point (no End Site away from its origin, no descendant at a non-zero OFFSET)
    gets three End Sites at d along its own x, y and z axes, d its OFFSET's length, else the
    median (the upper of an even count) of the skeleton's non-zero OFFSET lengths. What `diff`
    and `reduce --position-tolerance` measure without `--shell`. Returns the joints given ends."""
    moves = [any(np.linalg.norm(e) > 0 for e in j.end_sites) for j in clip.joints]
    for i in reversed(range(len(clip.joints))):
        j = clip.joints[i]
        if j.parent >= 0:
            moves[j.parent] = moves[j.parent] or moves[i] or bool(np.linalg.norm(j.offset) > 0)
    lengths = sorted(float(np.linalg.norm(j.offset)) for j in clip.joints
                     if np.linalg.norm(j.offset) > 0)
    median = lengths[len(lengths) // 2] if lengths else None
    given = []
    for i, j in enumerate(clip.joints):
        if not j.rot_cols or moves[i]:
            continue
        d = float(np.linalg.norm(j.offset)) or median
        if d is None:
            continue
        j.end_sites = list(j.end_sites) + [np.array(v, dtype=float) * d for v in np.eye(3)]
        given.append(j.name)
    return given


def world_points(clip, rotations, translations):
    """World positions of every joint origin and End Site at every frame: (frames, points, 3),
    points in file order (each joint's origin, then its End Sites). `rotations` {joint: (n, 4)}
    and `translations` {joint: (n, 3)} replace the clip's own (missing: identity / OFFSET)."""
    n = clip.frames
    wr = [None] * len(clip.joints)
    wp = [None] * len(clip.joints)
    pts = []
    eye = np.broadcast_to(np.eye(3), (n, 3, 3))
    for ji, j in enumerate(clip.joints):
        r = quat_to_matrix(rotations[ji]) if ji in rotations else eye
        t = translations[ji] if ji in translations else np.broadcast_to(j.offset, (n, 3))
        if j.parent < 0:
            wr[ji], wp[ji] = r, np.array(t, dtype=float)
        else:
            pr, pp = wr[j.parent], wp[j.parent]
            wr[ji] = pr @ r
            wp[ji] = pp + np.einsum("nij,nj->ni", pr, t)
        pts.append(wp[ji])
        for e in j.end_sites:
            pts.append(wp[ji] + wr[ji] @ e)
    return np.stack(pts, axis=1)


def point_labels(clip):
    out = []
    for j in clip.joints:
        out.append(j.name)
        out += [f"{j.name}/End Site"] * len(j.end_sites)
    return out
