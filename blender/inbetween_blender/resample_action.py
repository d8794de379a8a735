# SPDX-License-Identifier: GPL-3.0-or-later
"""Resample action: an action's rotation and location channels put onto the exact clock of
another rate, through the curves ``inbetween interp`` builds.

Every whole frame of the action (at the scene's exact rate, ``rates.scene_rate``) is a key, as
``inbetween interp --key-fps SCENE --fps OUT`` reads dense frames; ``inbetween.resample`` gives
the rotations (and locations) at the output frames, times ``k/OUT`` seconds after the action's
first frame, ``inbetween.frame_times`` those times. They are written as ``LINEAR`` keys at the
Blender frame numbers of those times at the scene's rate: ``first + k·SCENE/OUT``, fractional
where the rates do not divide (120 → 29.97: 0, 4.004, 8.008, …). Quaternion keys are written each
in the previous one's hemisphere; Euler keys as the Euler angles of the mode's order nearest the
previous key's (Blender's ``to_euler(order, compatible)``), starting from the action's first
frame, so the turns the channels made are kept.
"""

from __future__ import annotations

import time
from typing import List

import numpy as np
from mathutils import Euler, Quaternion

from . import channels, playback, rates
from .channels import QUATERNION, Target


def ensure_channels(obj, targets: List[Target]) -> bool:
    """Give every animated rotation (and location) of ``targets`` all its channels: a channel
    without an F-curve gets one (keyed at its value at the first frame), so the resampled
    rotation can be written whole. Returns whether any was made."""
    made = False
    for t in targets:
        owner = obj.pose.bones[t.name] if t.prefix else obj
        prop = "rotation_quaternion" if t.mode == QUATERNION else "rotation_euler"
        for group, path in ((t.rotation, prop), (t.location, "location")):
            if any(fc is not None for fc in group):
                first = min(fc.keyframe_points[0].co[0] for fc in group if fc is not None)
                for i, fc in enumerate(group):
                    if fc is None:
                        owner.keyframe_insert(data_path=path, index=i, frame=first)
                        made = True
    return made


def resample_object(obj, scene, targets: List[Target], fps_out: str, scheme: str) -> dict:
    """Resample every target of ``obj`` to ``fps_out`` (text, as ``inbetween`` reads a rate)."""
    import inbetween

    start = time.perf_counter()
    rate_in = rates.scene_rate(scene)
    f0, f1 = playback.frame_range([fc for t in targets for fc in t.fcurves()])
    frames = np.arange(f0, f1 + 1, dtype=np.float64)
    q = np.stack([playback.rotations(t.mode, playback.sample(t.rotation, t.rest_rotation, frames))
                  if t.has_rotation else np.tile([1.0, 0.0, 0.0, 0.0], (len(frames), 1))
                  for t in targets], axis=1)
    loc = np.stack([playback.sample(t.location, t.rest_location, frames) for t in targets], axis=1)
    first_euler = [playback.sample(t.rotation, t.rest_rotation, frames[:1])[0]
                   if t.mode != QUATERNION else None for t in targets]
    out_q, out_loc = inbetween.resample(q, rates.as_text(rate_in), fps_out, scheme=scheme,
                                        translations=loc)
    times = inbetween.frame_times(len(frames), rates.as_text(rate_in), fps_out)
    at = f0 + times * float(rate_in)
    keys_before = sum(len(fc.keyframe_points) for t in targets for fc in t.fcurves())
    for j, t in enumerate(targets):
        if t.has_rotation:
            if t.mode == QUATERNION:
                values = playback.hemisphere_continuous(out_q[:, j])
            else:
                values = _eulers(out_q[:, j], t.mode, first_euler[j])
            for i, fc in enumerate(t.rotation):
                playback.write_linear(fc, at, values[:, i])
        if t.has_location:
            for i, fc in enumerate(t.location):
                playback.write_linear(fc, at, out_loc[:, j, i])
    keys_after = sum(len(fc.keyframe_points) for t in targets for fc in t.fcurves())
    return {"frames_in": len(frames), "frames_out": len(times), "rate_in": rate_in,
            "keys_before": keys_before, "keys_after": keys_after,
            "first": f0, "last": float(at[-1]), "seconds": time.perf_counter() - start}


def _eulers(q: np.ndarray, order: str, first) -> np.ndarray:
    """Euler angles (K, 3) of quaternions (K, 4) in ``order``, each the triple nearest the one
    before (the first nearest ``first``, the action's own angles at its first frame)."""
    out = np.empty((len(q), 3))
    prev = Euler(first, order)
    for k, row in enumerate(q):
        e = Quaternion(row).to_euler(order, prev)
        out[k] = tuple(e)
        prev = e
    return out


def collect(obj, only_selected: bool) -> List[Target]:
    """The targets to resample, each with all its rotation (and location) channels."""
    targets = channels.targets(obj, only_selected)
    if ensure_channels(obj, targets):
        targets = channels.targets(obj, only_selected)
    return targets
