# SPDX-License-Identifier: GPL-3.0-or-later
"""The F-curves of an object's action, found the same way on every Blender from 4.2 LTS on.

Blender 4.2 and 4.3 keep an action's F-curves in ``action.fcurves``. From 4.4 an action may be
*layered*: its F-curves live in a channelbag per action slot,
``action.layers[0].strips[0].channelbag(slot)``, and the object names its slot
(``animation_data.action_slot``); Blender 5.0 removed ``action.fcurves``. ``action_fcurves`` is the
one place that knows both.

A *target* is what one rotation belongs to: a pose bone (data paths ``pose.bones["Name"].…``) or
the object itself (``rotation_quaternion``, ``rotation_euler``, ``location``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Dict, List, Optional

QUATERNION = "QUATERNION"
EULER_ORDERS = ("XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX")


def action_fcurves(id_data) -> Optional[list]:
    """The F-curves that animate ``id_data`` through its action, or None without an action.

    Layered actions (4.4+): the channelbag of the object's slot in the first strip that has
    one; legacy actions (4.2, 4.3, and 4.4 actions not yet layered): ``action.fcurves``."""
    ad = id_data.animation_data
    if ad is None or ad.action is None:
        return None
    action = ad.action
    layered = getattr(action, "is_action_layered", False) or not hasattr(action, "fcurves")
    if not layered:
        return list(action.fcurves)
    slot = getattr(ad, "action_slot", None)
    if slot is None:
        return []
    for layer in action.layers:
        for strip in layer.strips:
            bag = strip.channelbag(slot)
            if bag is not None:
                return list(bag.fcurves)
    return []


@dataclass
class Target:
    """One rotating thing: its name, data path prefix, rotation mode and F-curves by channel.

    ``rotation`` holds the F-curves of the channels its rotation mode plays
    (``rotation_quaternion`` w, x, y, z or ``rotation_euler`` x, y, z; None for a channel that
    is not animated), ``location`` those of x, y, z; ``rest_*`` the values Blender uses for a
    channel without an F-curve (the property's current value)."""

    name: str
    prefix: str
    mode: str
    rotation: List[Optional[object]] = field(default_factory=list)
    location: List[Optional[object]] = field(default_factory=list)
    rest_rotation: List[float] = field(default_factory=list)
    rest_location: List[float] = field(default_factory=list)
    bone_length: float = 0.0

    @property
    def has_rotation(self) -> bool:
        return any(fc is not None for fc in self.rotation)

    @property
    def has_location(self) -> bool:
        return any(fc is not None for fc in self.location)

    def fcurves(self) -> list:
        """The animated channels this target's reduction rewrites."""
        return [fc for fc in self.rotation + self.location if fc is not None]


def _bone_selected(pose_bone) -> bool:
    # Blender 5.0 keeps the selection on the pose bone, earlier versions on the bone.
    if "select" in pose_bone.bl_rna.properties:
        return bool(pose_bone.select)
    return bool(pose_bone.bone.select)


def targets(obj, only_selected: bool) -> List[Target]:
    """The targets of ``obj``'s action: its pose bones for an armature (the selected ones when
    ``only_selected`` and any is selected), else the object itself; those that have an animated
    rotation (of their rotation mode's kind) or location channel. Targets in axis-angle mode
    are left out (:func:`skipped_axis_angle` names them)."""
    fcurves = action_fcurves(obj) or []
    by_path: Dict[str, Dict[int, object]] = {}
    for fc in fcurves:
        by_path.setdefault(fc.data_path, {})[fc.array_index] = fc
    owners = []
    if obj.type == "ARMATURE" and obj.pose is not None:
        bones = list(obj.pose.bones)
        if only_selected and any(_bone_selected(pb) for pb in bones):
            bones = [pb for pb in bones if _bone_selected(pb)]
        owners = [(pb, pb.name, f'pose.bones["{_escape(pb.name)}"].', pb.bone.length) for pb in bones]
    else:
        owners = [(obj, obj.name, "", 0.0)]
    out = []
    for owner, name, prefix, length in owners:
        mode = owner.rotation_mode
        if mode == QUATERNION:
            path, n, rest = "rotation_quaternion", 4, list(owner.rotation_quaternion)
        elif mode in EULER_ORDERS:
            path, n, rest = "rotation_euler", 3, list(owner.rotation_euler)
        else:  # AXIS_ANGLE: not reduced (skipped_axis_angle names them)
            continue
        rot = [by_path.get(prefix + path, {}).get(i) for i in range(n)]
        loc = [by_path.get(prefix + "location", {}).get(i) for i in range(3)]
        t = Target(name, prefix, mode, rot, loc, rest, list(owner.location), length)
        if t.has_rotation or t.has_location:
            out.append(t)
    return out


def skipped_axis_angle(obj, only_selected: bool) -> List[str]:
    """Names of the bones (or the object) animated in axis-angle mode, which are not reduced."""
    fcurves = action_fcurves(obj) or []
    paths = {fc.data_path for fc in fcurves}
    if obj.type == "ARMATURE" and obj.pose is not None:
        bones = list(obj.pose.bones)
        if only_selected and any(_bone_selected(pb) for pb in bones):
            bones = [pb for pb in bones if _bone_selected(pb)]
        return [pb.name for pb in bones if pb.rotation_mode == "AXIS_ANGLE"
                and f'pose.bones["{_escape(pb.name)}"].rotation_axis_angle' in paths]
    if obj.rotation_mode == "AXIS_ANGLE" and "rotation_axis_angle" in paths:
        return [obj.name]
    return []


def _escape(name: str) -> str:
    """A bone name as Blender quotes it inside a data path."""
    return name.replace("\\", "\\\\").replace('"', '\\"')
