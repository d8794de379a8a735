# SPDX-License-Identifier: GPL-3.0-or-later
"""F-curves as Blender plays them: sampled by ``FCurve.evaluate``, rotations made as the pose
evaluation makes them, and keys written back as ``LINEAR`` keyframes.

Blender plays a bone's (or object's) rotation from its channels' values at the frame:
``rotation_quaternion`` as the four values normalised (``BKE_pchan_rot_to_mat3`` normalises the
quaternion before it becomes a matrix), so ``LINEAR`` quaternion keys play as the normalised
lerp of their components (nlerp); ``rotation_euler`` as the three angles in the mode's order
(mode ``XYZ`` turns about X, then Y, then Z, fixed axes: R = Rz·Ry·Rx), each channel lerped on
its own between ``LINEAR`` keys. A channel without an F-curve plays its property's value.
Quaternions here are (w, x, y, z), as Blender stores them.
"""

from __future__ import annotations

from typing import List, Optional, Sequence

import numpy as np
from mathutils import Euler

from .channels import QUATERNION


def frame_range(fcurves: Sequence) -> tuple:
    """The whole frames covering every key of ``fcurves``: (first, last), integers. F-curves
    without keys are an error (``ValueError``) when no F-curve has one."""
    keyed = [fc for fc in fcurves if len(fc.keyframe_points)]
    if not keyed:
        raise ValueError("the channels have no keyframes")
    lo = min(fc.keyframe_points[0].co[0] for fc in keyed)
    hi = max(fc.keyframe_points[-1].co[0] for fc in keyed)
    return int(np.floor(lo + 1e-6)), int(np.ceil(hi - 1e-6))


def sample(channels: List[Optional[object]], rest: Sequence[float], frames: np.ndarray) -> np.ndarray:
    """(T, n) values of ``channels`` at ``frames`` as ``FCurve.evaluate`` gives them; a channel
    that has no F-curve holds its ``rest`` value."""
    out = np.empty((len(frames), len(channels)))
    for i, fc in enumerate(channels):
        if fc is None:
            out[:, i] = rest[i]
        else:
            ev = fc.evaluate
            out[:, i] = [ev(f) for f in frames]
    return out


def rotations(mode: str, values: np.ndarray) -> np.ndarray:
    """(T, 4) unit quaternions (w, x, y, z) of channel values (T, 4) or (T, 3) as Blender's pose
    evaluation turns them into a rotation (``mode`` QUATERNION or an Euler order)."""
    if mode == QUATERNION:
        n = np.linalg.norm(values, axis=1, keepdims=True)
        if np.any(n == 0):
            # Blender plays a zero quaternion as the identity.
            values = np.where(n == 0, [1.0, 0.0, 0.0, 0.0], values)
            n = np.where(n == 0, 1.0, n)
        return values / n
    return np.array([tuple(Euler(v, mode).to_quaternion()) for v in values], dtype=np.float64)


def angles(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Geodesic angles (rad) between unit quaternions a and b (..., 4), sign-blind, computed as
    2·atan2(|vector part of a⁻¹b|, |its scalar|): accurate near 0, where acos of a dot is not."""
    aw, av = a[..., :1], -a[..., 1:]
    bw, bv = b[..., :1], b[..., 1:]
    w = aw[..., 0] * bw[..., 0] - np.sum(av * bv, axis=-1)
    v = aw * bv + bw * av + np.cross(av, bv)
    return 2.0 * np.arctan2(np.linalg.norm(v, axis=-1), np.abs(w))


def hemisphere_continuous(q: np.ndarray) -> np.ndarray:
    """``q`` (K, 4) with each row's sign flipped into the hemisphere of the row before (as
    written, so that a player blending components takes the short way, as nlerp's keys do)."""
    out = np.array(q, dtype=np.float64)
    for k in range(1, len(out)):
        if np.dot(out[k], out[k - 1]) < 0.0:
            out[k] = -out[k]
    return out


def _linear_value() -> int:
    import bpy

    return bpy.types.Keyframe.bl_rna.properties["interpolation"].enum_items["LINEAR"].value


def write_linear(fcurve, frames: np.ndarray, values: np.ndarray) -> None:
    """Replace every keyframe of ``fcurve`` by ``LINEAR`` keys (frames[i], values[i])."""
    n = len(frames)
    kp = fcurve.keyframe_points
    kp.clear()
    kp.add(n)
    co = np.empty(2 * n, dtype=np.float32)
    co[0::2] = frames
    co[1::2] = values
    kp.foreach_set("co", co)
    kp.foreach_set("handle_left", co)
    kp.foreach_set("handle_right", co)
    kp.foreach_set("interpolation", np.full(n, _linear_value(), dtype=np.int32))
    fcurve.update()
