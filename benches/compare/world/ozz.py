"""ozz-animation's keyframe optimizer rule, reimplemented in numpy (float64) for
benches/compare/world/compare.py, and the replay that measures its real world-space error.

Source read: guillaumeblanc/ozz-animation at commit 6cbdc790123aa4731d82e255df187b3a8a808256
(merge of release/0.16.0, 2025-01-19; the three files below last changed in ca1a4f0d, 2024-05-22):

- `src/animation/offline/animation_optimizer.cc` — `HierarchyBuilder` and
  `AnimationOptimizer::operator()`;
- `include/ozz/animation/offline/animation_optimizer.h` — `Setting`: `tolerance = 1e-3f` ("1mm",
  "the maximum error that an optimization is allowed to generate on a whole joint hierarchy"),
  `distance = 1e-1f` ("10cm", "the distance (from the joint) at which error is measured (if
  bigger than joint hierarchy). This allows to emulate effect on skinning");
- `src/animation/offline/decimate.h` — `Decimate()` (the brief said include/…; it is under src/);
- `src/animation/offline/raw_animation_utils.cc` — `LerpRotation` (NLerp after flipping the
  second quaternion to the first's hemisphere), `LerpTranslation` (lerp), and `SampleTrack`
  (before the first key: the first; after the last: the last; no key: identity).

The rule, as written there:

1. Hierarchical length and scale (`HierarchyBuilder`). Forward (root to leaves): each joint's
   scale is the largest animated scale component times its parent's (BVH: no scales, so 1);
   its length starts at `distance · scale` and its tolerance at `tolerance`. Backward (leaves to
   root): for each non-root joint, with `max_length` the largest length of its translation keys,
   `parent.length = max(parent.length, joint.length + max_length · parent.scale)` and
   `parent.tolerance = min(parent.tolerance, joint.tolerance)`. So a joint's length is its
   longest child chain (sum of the children's largest translations down to a leaf) plus
   `distance`. (Per-joint setting overrides are not used here.)
2. Per joint, each track decimated on its own (`Decimate`, Ramer–Douglas–Peucker): start with
   the first and last keys; for a segment, look for the interior key farthest from the
   interpolation between the segment's two ends at its time, among those farther than the
   tolerance (`distance > _tolerance && distance > max`); if there is one, keep it and push the
   two halves. Distances (the adapters):
   - rotation: `2·sin(θ/2)·length`, θ the angle between the key and the NLerp of the ends,
     `length` the joint's hierarchical length (the chord a point at that length moves);
   - translation: `|Δt|·parent_scale`.
   Then trailing keys are dropped while the last key is within the tolerance of the one
   before, and a lone last key is dropped if within the tolerance of identity (the track
   then plays identity): a held end costs no key.
3. Playback (what the optimizer assumes): `LerpRotation`, i.e. **normalised lerp** on the
   shortest path, and lerp for translations, between the two kept keys around the time, the
   first/last key held outside them. The runtime `SamplingJob` (src/animation/runtime/
   sampling_job.cc, `Interpolates`) also plays NLerp (`NLerpEst`, with an estimated reciprocal
   square root) between keys that `AnimationBuilder` has quantised (rotations: three smallest
   components on integers; translations: half floats). This replay uses exact NLerp on the
   unquantised keys, i.e. the optimizer's own model, so the error measured is that of the
   decimation alone.

Where this differs from ozz (simplifications):

- float64 throughout (ozz: float32), so ties at the tolerance may fall differently;
- the BVH is mapped to a RawAnimation as an importer would: every joint a track with a rotation
  track (its Euler channels through scipy, intrinsic in the listed order; identity when it has
  none) and a translation track (its position channels where it has any, else its OFFSET as a
  constant); every End Site a leaf joint with its OFFSET as a constant translation, so it counts
  in its parent's hierarchical length (ozz's importers make end nodes joints too);
- keys at every frame of the BVH (frame i at time i·frame_time), no resampling;
- `tolerance` and `distance` are in the clip's length units (ozz's are metres): compare.py
  passes LEN converted to the clip's units, and `distance` 0 (the points measured are the
  joints and End Sites, which the hierarchical length already reaches) or ozz's default 10 cm.
- keys counted per joint with channels: the union of the frames of its rotation keys and, for a
  joint with position channels, its translation keys (a BVH-style key carries both, as
  inbetween's do); translation tracks of joints without position channels are the rest OFFSET
  and not counted. A held track may keep 1 or 0 keys (inbetween keeps at least 2).

Its bound is per track: each joint's own decimation moves the points of its hierarchy by at
most `tolerance`; nothing bounds the sum along a chain, so its world error is measured, not
assumed (`world_error`).
"""
import numpy as np

import bvh


def nlerp(a, b, u):
    """ozz LerpRotation: b flipped to a's hemisphere, lerp, normalise. a, b (..., 4), u (...)."""
    d = np.sum(a * b, axis=-1, keepdims=True)
    b = np.where(d < 0, -b, b)
    r = a + (b - a) * u[..., None]
    return r / np.linalg.norm(r, axis=-1, keepdims=True)


def rot_distance(a, b, radius):
    """ozz RotationAdapter::Distance: 2·sin(half angle)·radius (sign-blind)."""
    c = np.abs(np.sum(a * b, axis=-1))
    s = np.sqrt(1.0 - np.minimum(1.0, c * c))
    return 2.0 * s * radius


def decimate(values, lerp, distance, identity, tol):
    """ozz Decimate() on a track with a key at every frame (index = time). Kept indices."""
    n = len(values)
    if n < 2:
        kept = list(range(n))
    else:
        included = np.zeros(n, dtype=bool)
        included[0] = included[n - 1] = True
        stack = [(0, n - 1)]
        while stack:
            a, b = stack.pop()
            if b - a < 2:
                continue
            i = np.arange(a + 1, b)
            u = (i - a) / (b - a)
            est = lerp(np.broadcast_to(values[a], (len(i),) + values.shape[1:]),
                       np.broadcast_to(values[b], (len(i),) + values.shape[1:]), u)
            d = distance(est, values[i])
            over = d > tol
            if not over.any():
                continue
            c = int(i[np.argmax(np.where(over, d, -1.0))])  # first of the largest, as ozz's `>`
            included[c] = True
            if c - a > 1:
                stack.append((a, c))
            if b - c > 1:
                stack.append((c, b))
        kept = list(np.nonzero(included)[0])
    # Trailing keys within the tolerance of the one before (or of identity) are dropped.
    while kept:
        prev = identity if len(kept) == 1 else values[kept[-2]]
        if distance(prev[None], values[kept[-1]][None])[0] > tol:
            break
        kept.pop()
    return kept


def lerp3(a, b, u):
    return a + (b - a) * u[..., None]


def dist3(a, b):
    return np.linalg.norm(a - b, axis=-1)


def hierarchical_lengths(clip, translations, distance):
    """HierarchyBuilder: per joint, its length (scale 1 everywhere: BVH has no scales).
    `translations` {joint: (n, 3)} the animated ones; End Sites are leaf joints."""
    nj = len(clip.joints)
    length = np.full(nj, float(distance))
    for ji in reversed(range(nj)):  # children come after their parents in file order
        j = clip.joints[ji]
        for e in j.end_sites:  # leaf joint: length = distance
            length[ji] = max(length[ji], distance + np.linalg.norm(e))
        if j.parent >= 0:
            if ji in translations:
                ml = float(np.max(np.linalg.norm(translations[ji], axis=1)))
            else:
                ml = float(np.linalg.norm(j.offset))
            length[j.parent] = max(length[j.parent], length[ji] + ml)
    return length


def optimize(clip, rotations, translations, tol, distance):
    """Kept frames per joint with channels: {joint: {"rot": [...], "pos": [...] or None}}, and the
    hierarchical lengths. rotations {joint: (n, 4)}, translations {joint: (n, 3)} (the clip's)."""
    length = hierarchical_lengths(clip, translations, distance)
    ident_q = np.array([1.0, 0.0, 0.0, 0.0])
    out = {}
    for ji in clip.tracks:
        r = None
        if ji in rotations:
            rad = length[ji]
            r = decimate(rotations[ji], nlerp, lambda a, b: rot_distance(a, b, rad), ident_q, tol)
        p = None
        if ji in translations:
            p = decimate(translations[ji], lerp3, dist3, np.zeros(3), tol)
        out[ji] = {"rot": r, "pos": p}
    return out, length


def sample(values, kept, n, lerp, identity):
    """SampleTrack on the kept keys at every frame 0..n-1."""
    if not kept:
        return np.broadcast_to(identity, (n,) + identity.shape).copy()
    k = np.asarray(kept)
    i = np.arange(n)
    if len(k) == 1:
        return np.broadcast_to(values[k[0]], (n,) + values.shape[1:]).copy()
    seg = np.clip(np.searchsorted(k, i, side="right") - 1, 0, len(k) - 2)
    a, b = k[seg], k[seg + 1]
    u = np.clip((i - a) / (b - a), 0.0, 1.0)
    return lerp(values[a], values[b], u)


def replay(clip, rotations, translations, kept):
    """The local tracks ozz plays from its kept keys, at every frame."""
    n = clip.frames
    rr, tt = {}, {}
    for ji, kk in kept.items():
        if kk["rot"] is not None:
            rr[ji] = sample(rotations[ji], kk["rot"], n, nlerp, np.array([1.0, 0.0, 0.0, 0.0]))
        if kk["pos"] is not None:
            tt[ji] = sample(translations[ji], kk["pos"], n, lerp3, np.zeros(3))
    return rr, tt


def key_count(kept):
    """Per joint with channels: union of rotation and translation key frames."""
    out = []
    for ji, kk in kept.items():
        s = set(kk["rot"] or []) | set(kk["pos"] or [])
        out.append(len(s))
    return out


def world_error(clip, ref_points, rotations, translations, kept):
    """Largest world displacement of any joint origin or End Site at any frame, and where."""
    rr, tt = replay(clip, rotations, translations, kept)
    pts = bvh.world_points(clip, rr, tt)
    d = np.linalg.norm(pts - ref_points, axis=-1)
    f, p = np.unravel_index(int(np.argmax(d)), d.shape)
    return float(d[f, p]), int(f), bvh.point_labels(clip)[p]
