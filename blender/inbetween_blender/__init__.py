# SPDX-License-Identifier: GPL-3.0-or-later
"""inbetween for Blender: Reduce Keys (verified in Blender's own playback) and Resample Action
(on an exact clock), in the Graph Editor's and Dope Sheet's Key and Channel menus.

The maths is the ``inbetween`` Python package (the wheel bundled with this extension), the same
code as the ``inbetween`` command line. docs/blender.md in the repository says what each operator
guarantees.
"""

import math

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, StringProperty

from . import channels, rates


def _animated(context) -> bool:
    obj = context.active_object
    return obj is not None and bool(channels.action_fcurves(obj))


class INBETWEEN_OT_reduce_keys(bpy.types.Operator):
    """Keep the fewest LINEAR keys that play back every frame within the tolerance, verified in
    Blender's own evaluation of the written F-curves"""

    bl_idname = "anim.inbetween_reduce_keys"
    bl_label = "Reduce Keys (inbetween)"
    bl_options = {"REGISTER", "UNDO"}

    tolerance: FloatProperty(
        name="Angle Tolerance",
        description="Largest angle between each bone's rotation as played back and as it was, "
                    "at every frame",
        subtype="ANGLE", default=math.radians(1.0), min=math.radians(1e-4), max=math.pi,
    )
    location_tolerance: FloatProperty(
        name="Location Tolerance",
        description="Largest distance between each bone's location channels as played back "
                    "and as they were, at every frame",
        subtype="DISTANCE", default=0.001, min=1e-7,
    )
    position_tolerance: FloatProperty(
        name="Position Tolerance",
        description="Armatures: also every bone's head and tail within this distance of where "
                    "they were, in the armature's space, at every frame (0: off)",
        subtype="DISTANCE", default=0.0, min=0.0,
    )
    shell: FloatProperty(
        name="Shell",
        description="With a position tolerance, also the three points this far from each "
                    "bone's head along its own axes, so that a twist about the bone counts "
                    "(0: heads and tails only)",
        subtype="DISTANCE", default=0.0, min=0.0,
    )
    only_selected: BoolProperty(
        name="Only Selected Bones",
        description="Reduce the selected pose bones only (all bones when none is selected)",
        default=True,
    )

    @classmethod
    def poll(cls, context):
        return _animated(context)

    def execute(self, context):
        from . import reduce_keys

        obj = context.active_object
        scene = context.scene
        targets = channels.targets(obj, self.only_selected)
        skipped = channels.skipped_axis_angle(obj, self.only_selected)
        if not targets:
            self.report({"WARNING"}, "No quaternion, Euler or location channels to reduce"
                        + (f" (axis-angle skipped: {', '.join(skipped)})" if skipped else ""))
            return {"CANCELLED"}
        try:
            result = reduce_keys.reduce_object(
                obj, scene, targets, rates.as_text(rates.scene_rate(scene)), self.tolerance,
                self.location_tolerance, self.position_tolerance, self.shell)
        except ValueError as e:  # inbetween.InputError
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        reductions = result["reductions"]
        before = sum(r.keys_before for r in reductions)
        after = sum(r.keys_after for r in reductions)
        worst = max(reductions, key=lambda r: r.angle_error)
        print(f"inbetween: Reduce Keys on {obj.name}, frames {result['frames'][0]}–"
              f"{result['frames'][1]}, {math.degrees(self.tolerance):.4g}°, "
              f"{result['seconds']:.2f} s")
        print(reduce_keys.table(result, any(r.target.has_location for r in reductions)))
        what = "bones" if obj.type == "ARMATURE" else "object"
        msg = (f"Reduced {len(reductions)} {what}: keys {before} → {after}; largest error "
               f"{math.degrees(worst.angle_error):.3f}° ({worst.target.name})")
        if result["worst_point"] is not None:
            msg += (f"; heads, tails{' and shells' if self.shell > 0 else ''} within "
                    f"{result['worst_point']:.3g}")
            print(f"inbetween: largest point displacement {result['worst_point']:.6g} "
                  f"after {result['world_rounds']} world-space round(s)")
        if skipped:
            msg += f"; axis-angle skipped: {', '.join(skipped)}"
        kept = [r.target.name for r in reductions if r.every_frame]
        if kept:
            msg += f"; every frame kept: {', '.join(kept)}"
        missed = [r.target.name for r in reductions
                  if r.angle_error > r.angle_tol or r.location_error > r.location_tol]
        if result["worst_point"] is not None and result["worst_point"] > self.position_tolerance:
            missed.append("position tolerance")
        if missed:
            self.report({"WARNING"}, msg + f"; NOT within the tolerance: {', '.join(missed)}")
        else:
            self.report({"INFO"}, msg)
        return {"FINISHED"}

    def invoke(self, context, event):
        return context.window_manager.invoke_props_dialog(self)


SCHEMES = [
    ("bezier", "Bézier", "Spherical Bézier through every frame (the command line's default)"),
    ("squad", "Squad", "Shoemake's squad through every frame"),
    ("hermite", "Hermite", "Cubic Hermite in the tangent space"),
    ("slerp", "Slerp", "Constant speed between frames"),
    ("nlerp", "Nlerp", "Normalised lerp of the components between frames"),
]


class INBETWEEN_OT_resample_action(bpy.types.Operator):
    """Put the action's rotation and location keys on the exact clock of another rate, through
    the curves of the inbetween command line (every whole frame a key)"""

    bl_idname = "anim.inbetween_resample_action"
    bl_label = "Resample Action (inbetween)"
    bl_options = {"REGISTER", "UNDO"}

    fps: StringProperty(
        name="Rate",
        description="Frames per second of the new keys: 30, 29.97 (30000/1001), 24, 30000/1001",
        default="30",
    )
    scheme: EnumProperty(name="Curve", items=SCHEMES, default="bezier")
    only_selected: BoolProperty(
        name="Only Selected Bones",
        description="Resample the selected pose bones only (all bones when none is selected)",
        default=True,
    )

    @classmethod
    def poll(cls, context):
        return _animated(context)

    def execute(self, context):
        import inbetween

        from . import resample_action

        obj = context.active_object
        try:  # the rate first: nothing is changed for a rate inbetween does not read
            inbetween.frame_times(1, "1", self.fps)
        except ValueError as e:
            self.report({"ERROR"}, f"Rate: {e}")
            return {"CANCELLED"}
        targets = resample_action.collect(obj, self.only_selected)
        if not targets:
            self.report({"WARNING"}, "No quaternion, Euler or location channels to resample")
            return {"CANCELLED"}
        try:
            r = resample_action.resample_object(obj, context.scene, targets, self.fps, self.scheme)
        except ValueError as e:  # inbetween.InputError
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        what = "bones" if obj.type == "ARMATURE" else "object"
        msg = (f"Resampled {len(targets)} {what}: {r['frames_in']} frames at "
               f"{rates.as_text(r['rate_in'])} fps → {r['frames_out']} keys at {self.fps} fps "
               f"(frames {r['first']}–{r['last']:.4f}), keys {r['keys_before']} → "
               f"{r['keys_after']}, {r['seconds']:.2f} s")
        print("inbetween: " + msg)
        self.report({"INFO"}, msg)
        return {"FINISHED"}

    def invoke(self, context, event):
        return context.window_manager.invoke_props_dialog(self)


def _menu(self, context):
    layout = self.layout
    layout.separator()
    layout.operator(INBETWEEN_OT_reduce_keys.bl_idname)
    layout.operator(INBETWEEN_OT_resample_action.bl_idname)


CLASSES = (INBETWEEN_OT_reduce_keys, INBETWEEN_OT_resample_action)
MENUS = ("GRAPH_MT_key", "DOPESHEET_MT_key", "GRAPH_MT_channel", "DOPESHEET_MT_channel")


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    for name in MENUS:
        getattr(bpy.types, name).append(_menu)


def unregister():
    for name in MENUS:
        getattr(bpy.types, name).remove(_menu)
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
