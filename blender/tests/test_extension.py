# SPDX-License-Identifier: GPL-3.0-or-later
"""The extension in headless Blender: installed from its zip, its operators run on a real mocap
clip imported by Blender's BVH importer, and every frame re-evaluated *independently* afterwards
— ``scene.frame_set`` and the pose bones' ``matrix_basis``, ``head`` and ``tail`` as Blender's pose
evaluation leaves them — against the same taken before the operator ran.

Tolerances: the operators promise their bounds on Blender's own evaluation of the F-curves; this
re-evaluation reads float32 matrices and positions, so ``FLOAT32_ANGLE`` (1e-4° = 1.7e-6 rad;
on CMU 01_01 a float32 ``matrix_basis`` is at most 2.4e-7 rad from the float64 rotation of its
own quaternion, measured through the skew part as below) and ``FLOAT32_LENGTH`` (1e-5 length
units, for positions within ±100: float32 carries 7.6e-6 there) are added to them.
"""

import csv
import importlib
import math
import os
import time
from fractions import Fraction

import bpy
import numpy as np
import pytest

from conftest import ROOT, clear, load_bvh, run_cli

FLOAT32_ANGLE = math.radians(1e-4)
FLOAT32_LENGTH = 1e-5
CLIP = "fixtures/bvh/cmu_01_01.bvh"
DEGREE = math.radians(1.0)
LOCATION = 0.001


def fcurves(ob):
    """The F-curves of ``ob``'s action, read here without the extension: a layered action's
    (Blender 4.4+) from its slot's channelbag, else ``action.fcurves`` (4.2 LTS)."""
    ad = ob.animation_data
    if getattr(ad.action, "is_action_layered", False):
        return list(ad.action.layers[0].strips[0].channelbag(ad.action_slot).fcurves)
    return list(ad.action.fcurves)


def select(pb, state):
    """Select a pose bone: on the pose bone from Blender 5.0, on its bone before."""
    if "select" in pb.bl_rna.properties:
        pb.select = state
    else:
        pb.bone.select = state


def whole_frames(ob):
    lo, hi = ob.animation_data.action.frame_range
    return list(range(int(lo), int(hi) + 1))


def pose(ob, frames):
    """What Blender shows at each frame: per bone the rotation (3×3) and translation of
    ``matrix_basis`` and the head and tail in the armature's space."""
    scene = bpy.context.scene
    bones = list(ob.pose.bones)
    rot = np.empty((len(frames), len(bones), 3, 3))
    loc = np.empty((len(frames), len(bones), 3))
    ends = np.empty((len(frames), len(bones), 2, 3))
    for i, f in enumerate(frames):
        scene.frame_set(f)
        for b, pb in enumerate(bones):
            m = np.array(pb.matrix_basis)
            rot[i, b], loc[i, b] = m[:3, :3], m[:3, 3]
            ends[i, b, 0], ends[i, b, 1] = pb.head, pb.tail
    return rot, loc, ends


def matrix_angles(a, b):
    """Angles (rad) of the rotations aᵀb, from their skew part and trace (accurate near 0)."""
    r = np.einsum("...ji,...jk->...ik", a, b)
    s = np.stack([r[..., 2, 1] - r[..., 1, 2], r[..., 0, 2] - r[..., 2, 0],
                  r[..., 1, 0] - r[..., 0, 1]], axis=-1)
    return np.arctan2(np.linalg.norm(s, axis=-1) / 2, (np.trace(r, axis1=-2, axis2=-1) - 1) / 2)


def quat_angles(a, b):
    d = np.abs(np.sum(a * b, axis=-1)) / (np.linalg.norm(a, axis=-1) * np.linalg.norm(b, axis=-1))
    c = np.cross(a[..., 1:], b[..., 1:]) + a[..., :1] * b[..., 1:] - b[..., :1] * a[..., 1:]
    return 2 * np.arctan2(np.linalg.norm(c, axis=-1) / (np.linalg.norm(a, axis=-1) * np.linalg.norm(b, axis=-1)), d)


def key_frames_per_bone(ob):
    """Per bone, its rotation channels' key count (each channel has the same keys)."""
    out = {}
    for fc in fcurves(ob):
        if ".rotation_" in fc.data_path and fc.array_index == 0:
            out[fc.data_path.split('"')[1]] = len(fc.keyframe_points)
    return out


def reference_keys(cli, tmp_path):
    """Key frames per joint of the command line's reduce for Blender's player (nlerp, no
    velocities: nlerp has no tangents) at 1° and the location tolerance, on the BVH file itself;
    the Python package's reduce when no command line was built."""
    import inbetween

    if cli is None:
        clip = inbetween.read(os.path.join(ROOT, CLIP))
        moving = clip.translations if clip.translations is not None else None
        r = inbetween.reduce(clip.rotations, clip.fps, 1.0, scheme="nlerp", velocities=False,
                             translations=moving, translation_tolerance=LOCATION)
        return "python", {n: len(k) for n, k in zip(clip.names, r.keys)}
    import json

    out = tmp_path / "keys.json"
    run_cli(cli, "reduce", os.path.join(ROOT, CLIP), "--scheme", "nlerp", "--no-velocities",
            "--tolerance", "1", "--translation-tolerance", str(LOCATION), "-o", str(out))
    doc = json.loads(out.read_text())
    return "cli", {t["name"]: len(t["keys"]) for t in doc["tracks"]}


def module(extension, name=None):
    """The installed extension's package, or one of its modules."""
    return importlib.import_module(extension if name is None else f"{extension}.{name}")


def test_installs_and_adds_menu_entries(extension):
    import inbetween

    assert bpy.ops.anim.inbetween_reduce_keys.idname() == "ANIM_OT_inbetween_reduce_keys"
    assert bpy.ops.anim.inbetween_resample_action.idname() == "ANIM_OT_inbetween_resample_action"
    # The package comes from the wheel the extension bundles, under the temporary user folder.
    assert inbetween.__file__.startswith(os.environ["BLENDER_USER_RESOURCES"]), inbetween.__file__
    draw = module(extension)._menu
    for menu in ("GRAPH_MT_key", "DOPESHEET_MT_key", "GRAPH_MT_channel", "DOPESHEET_MT_channel"):
        assert draw in getattr(bpy.types, menu)._dyn_ui_initialize(), menu


@pytest.mark.parametrize("mode", ["QUATERNION", "NATIVE", "XYZ"])
def test_reduce_keys_holds_one_degree_at_every_frame(extension, cli, mode, tmp_path):
    ob = load_bvh(mode)
    frames = whole_frames(ob)
    rot0, loc0, _ = pose(ob, frames)
    keys_before = sum(len(fc.keyframe_points) for fc in fcurves(ob))
    start = time.perf_counter()
    assert bpy.ops.anim.inbetween_reduce_keys(tolerance=DEGREE, location_tolerance=LOCATION,
                                              only_selected=False) == {"FINISHED"}
    seconds = time.perf_counter() - start
    rot1, loc1, _ = pose(ob, frames)
    err = matrix_angles(rot0, rot1)
    worst = np.unravel_index(np.argmax(err), err.shape)
    names = [pb.name for pb in ob.pose.bones]
    assert err.max() <= DEGREE + FLOAT32_ANGLE, (
        f"{names[worst[1]]} at frame {frames[worst[0]]}: {math.degrees(err.max())}°")
    dloc = np.linalg.norm(loc1 - loc0, axis=-1)
    assert dloc.max() <= LOCATION + FLOAT32_LENGTH, dloc.max()
    # Every key written is LINEAR, and reduced: fewer keys than frames on the moving bones.
    for fc in fcurves(ob):
        assert all(k.interpolation == "LINEAR" for k in fc.keyframe_points), fc.data_path
    keys_after = sum(len(fc.keyframe_points) for fc in fcurves(ob))
    assert keys_after < keys_before / 2
    # The same player's keys from the command line, on the file: within 10 %.
    source, ref = reference_keys(cli, tmp_path)
    mine = key_frames_per_bone(ob)
    assert set(mine) == set(ref), (set(mine) ^ set(ref))
    total, ref_total = sum(mine.values()), sum(ref.values())
    assert abs(total - ref_total) <= 0.10 * ref_total, (total, ref_total)
    print(f"\nFIGURES reduce {mode}: {len(frames)} frames x {len(names)} bones, keys "
          f"{keys_before} -> {keys_after} (key frames {total}, {source} reduce --scheme nlerp: "
          f"{ref_total}), worst {math.degrees(err.max()):.4f}° ({names[worst[1]]}), worst "
          f"location {dloc.max():.2e}, {seconds:.3f} s")


def test_the_independent_check_sees_unverified_euler_keys(extension, monkeypatch):
    """Negative control: with the operator's own verification switched off (every measured error
    reported as 0), nlerp's keys written on Euler channels — which Blender lerps per channel —
    leave some bone beyond 1° at some frame, and the re-evaluation above finds it."""
    reduce_keys = module(extension, "reduce_keys")

    def blind(self):
        self.angle_error = self.location_error = 0.0

    monkeypatch.setattr(reduce_keys.TargetReduction, "_measure", blind)
    ob = load_bvh("NATIVE")
    frames = whole_frames(ob)
    rot0, _, _ = pose(ob, frames)
    assert bpy.ops.anim.inbetween_reduce_keys(tolerance=DEGREE, only_selected=False) == {"FINISHED"}
    rot1, _, _ = pose(ob, frames)
    err = matrix_angles(rot0, rot1)
    assert err.max() > DEGREE + FLOAT32_ANGLE, math.degrees(err.max())
    print(f"\nFIGURES negative control: unverified Euler keys miss by up to "
          f"{math.degrees(err.max()):.3f}°")


def test_position_tolerance_bounds_heads_and_tails(extension):
    limit = 0.05
    ob = load_bvh("QUATERNION")
    frames = whole_frames(ob)
    _, _, ends0 = pose(ob, frames)
    assert bpy.ops.anim.inbetween_reduce_keys(tolerance=DEGREE, only_selected=False) == {"FINISHED"}
    _, _, ends1 = pose(ob, frames)
    plain = np.linalg.norm(ends1 - ends0, axis=-1).max()
    plain_keys = sum(len(fc.keyframe_points) for fc in fcurves(ob))
    assert plain > limit, plain  # 1° alone does not bound them: the check below can fail

    ob = load_bvh("QUATERNION")
    assert bpy.ops.anim.inbetween_reduce_keys(tolerance=DEGREE, position_tolerance=limit,
                                              only_selected=False) == {"FINISHED"}
    rot1, _, ends1 = pose(ob, frames)
    d = np.linalg.norm(ends1 - ends0, axis=-1)
    assert d.max() <= limit + FLOAT32_LENGTH, d.max()
    keys = sum(len(fc.keyframe_points) for fc in fcurves(ob))
    print(f"\nFIGURES position tolerance {limit}: heads/tails within {d.max():.4f} "
          f"(1° alone: {plain:.4f}), keys {plain_keys} -> {keys}")


def shell_points(ob, frames, shell):
    """(T, B, 3, 3): the points ``shell`` along each bone's x, y, z from its head, computed here
    from ``pose_bone.matrix`` (armature space) at each frame."""
    scene = bpy.context.scene
    out = np.empty((len(frames), len(ob.pose.bones), 3, 3))
    for i, f in enumerate(frames):
        scene.frame_set(f)
        for b, pb in enumerate(ob.pose.bones):
            m = np.array(pb.matrix)
            for a in range(3):
                out[i, b, a] = m[:3, 3] + shell * m[:3, a]
    return out


def test_shell_bounds_twists(extension):
    """Heads and tails do not see a twist about a bone; the shell's points do."""
    limit, shell = 0.05, 5.0
    ob = load_bvh("QUATERNION")
    frames = whole_frames(ob)
    s0 = shell_points(ob, frames, shell)
    assert bpy.ops.anim.inbetween_reduce_keys(tolerance=DEGREE, position_tolerance=limit,
                                              only_selected=False) == {"FINISHED"}
    without = np.linalg.norm(shell_points(ob, frames, shell) - s0, axis=-1).max()
    assert without > limit, without  # heads and tails alone leave the shell outside

    ob = load_bvh("QUATERNION")
    _, _, ends0 = pose(ob, frames)
    assert bpy.ops.anim.inbetween_reduce_keys(tolerance=DEGREE, position_tolerance=limit,
                                              shell=shell, only_selected=False) == {"FINISHED"}
    d = np.linalg.norm(shell_points(ob, frames, shell) - s0, axis=-1).max()
    assert d <= limit + FLOAT32_LENGTH, d
    _, _, ends1 = pose(ob, frames)
    assert np.linalg.norm(ends1 - ends0, axis=-1).max() <= limit + FLOAT32_LENGTH
    keys = sum(len(fc.keyframe_points) for fc in fcurves(ob))
    print(f"\nFIGURES shell {shell} at {limit}: shell points within {d:.4f} (heads and tails "
          f"alone: {without:.4f}), keys {keys}")


def test_only_selected_bones_are_reduced(extension):
    ob = load_bvh("QUATERNION")
    chosen = {"LeftLeg", "RightArm"}
    for pb in ob.pose.bones:
        select(pb, pb.name in chosen)
    before = key_frames_per_bone(ob)
    assert bpy.ops.anim.inbetween_reduce_keys(tolerance=DEGREE) == {"FINISHED"}
    after = key_frames_per_bone(ob)
    for name in before:
        if name in chosen:
            assert after[name] < before[name], name
        else:
            assert after[name] == before[name], name


def original_channels(ob, frames):
    """Per bone, at each frame, the rotation (unit quaternion w, x, y, z, as Blender turns the
    channels into one) and the location channels, as Blender evaluated them."""
    scene = bpy.context.scene
    bones = list(ob.pose.bones)
    q = np.empty((len(frames), len(bones), 4))
    loc = np.empty((len(frames), len(bones), 3))
    for i, f in enumerate(frames):
        scene.frame_set(f)
        for b, pb in enumerate(bones):
            r = (pb.rotation_quaternion.normalized() if pb.rotation_mode == "QUATERNION"
                 else pb.rotation_euler.to_quaternion())
            q[i, b], loc[i, b] = tuple(r), tuple(pb.location)
    return q, loc


def cli_interp(cli, tmp_path, names, q, loc, fps_in, fps_out):
    """``inbetween interp --key-fps IN --fps OUT`` of the frames as a CSV: (M, J, 4), (M, J, 3)."""
    src, out = tmp_path / "frames.csv", tmp_path / "out.csv"
    with open(src, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["track", "frame", "w", "x", "y", "z", "tx", "ty", "tz"])
        for j, name in enumerate(names):
            for i in range(len(q)):
                w.writerow([name, i, *map(repr, q[i, j]), *map(repr, loc[i, j])])
    run_cli(cli, "interp", str(src), "--key-fps", fps_in, "--fps", fps_out, "-o", str(out))
    rows = list(csv.DictReader(open(out)))
    m = len(rows) // len(names)
    rq = np.array([[float(r[c]) for c in "wxyz"] for r in rows]).reshape(len(names), m, 4)
    rl = np.array([[float(r[c]) for c in ("tx", "ty", "tz")] for r in rows]).reshape(len(names), m, 3)
    return rq.transpose(1, 0, 2), rl.transpose(1, 0, 2)


@pytest.mark.parametrize("mode,fps_out", [("QUATERNION", "30"), ("QUATERNION", "29.97"),
                                          ("NATIVE", "30000/1001"), ("XYZ", "30")])
def test_resample_puts_frames_on_the_exact_clock(extension, cli, tmp_path, mode, fps_out):
    import inbetween

    ob = load_bvh(mode)
    scene = bpy.context.scene
    assert (scene.render.fps, round(scene.render.fps_base, 6)) == (120, 0.999996)  # Frame Time .0083333
    frames = whole_frames(ob)
    q0, loc0 = original_channels(ob, frames)
    names = [pb.name for pb in ob.pose.bones]
    start = time.perf_counter()
    assert bpy.ops.anim.inbetween_resample_action(fps=fps_out, only_selected=False) == {"FINISHED"}
    seconds = time.perf_counter() - start

    # The exact clock, derived here: output frame k at k/OUT s, Blender frame first + k·120/OUT.
    out_rate = {"29.97": Fraction(30000, 1001)}.get(fps_out) or Fraction(fps_out)
    m = math.floor(Fraction(len(frames) - 1, 120) * out_rate) + 1
    at = [frames[0] + k * Fraction(120) / out_rate for k in range(m)]
    exact = np.array(at, dtype=float)
    ulps = 2 * np.spacing(exact.astype(np.float32)).astype(float)  # key frames are float32
    for fc in fcurves(ob):
        co = np.array([k.co[0] for k in fc.keyframe_points])
        assert len(co) == m, (fc.data_path, len(co), m)
        assert np.all(np.abs(co - exact) <= ulps), (fc.data_path, np.abs(co - exact).max())
    # The check tells clocks apart: Blender's own rate for this scene, 120/0.999996 = 120.00048,
    # would put the last key off by more than that.
    drifted = frames[0] + np.arange(m) * (scene.render.fps / scene.render.fps_base) / float(out_rate)
    assert np.abs(drifted - exact)[-1] > ulps[-1]

    expected_q, expected_loc = inbetween.resample(q0, "120", fps_out, translations=loc0)
    got_q = np.empty_like(expected_q)
    got_loc = np.empty_like(expected_loc)
    for k, f in enumerate(at):
        whole = math.floor(f)
        scene.frame_set(whole, subframe=float(f - whole))
        for b, pb in enumerate(ob.pose.bones):
            r = (pb.rotation_quaternion if pb.rotation_mode == "QUATERNION"
                 else pb.rotation_euler.to_quaternion())
            got_q[k, b], got_loc[k, b] = tuple(r), tuple(pb.location)
    err = quat_angles(got_q, expected_q)
    assert err.max() <= 1e-5, math.degrees(err.max())
    lerr = np.abs(got_loc - expected_loc).max()
    assert lerr <= 1e-5 * max(1.0, np.abs(expected_loc).max()), lerr
    line = (f"\nFIGURES resample {mode} 120 -> {fps_out}: {len(frames)} frames -> {m} keys, "
            f"largest angle to inbetween.resample {math.degrees(err.max()):.2e}°, location "
            f"{lerr:.1e}")
    if cli is not None:
        cq, cl = cli_interp(cli, tmp_path, names, q0, loc0, "120", fps_out)
        cerr = quat_angles(got_q, cq)
        assert cerr.max() <= 1e-5, math.degrees(cerr.max())
        assert np.abs(got_loc - cl).max() <= 1e-5 * max(1.0, np.abs(cl).max())
        line += f", to the CLI's interp {math.degrees(cerr.max()):.2e}°"
    print(line + f", {seconds:.3f} s")


def test_resample_refuses_a_rate_it_cannot_read_and_fills_missing_channels(extension):
    ob = load_bvh("XYZ")
    # Spine without its Y rotation channel: Resample would give it one before writing.
    ad = ob.animation_data
    owner = (ad.action.layers[0].strips[0].channelbag(ad.action_slot)
             if getattr(ad.action, "is_action_layered", False) else ad.action)
    owner.fcurves.remove(next(fc for fc in fcurves(ob) if fc.data_path ==
                              'pose.bones["Spine"].rotation_euler' and fc.array_index == 1))
    before = {(fc.data_path, fc.array_index): len(fc.keyframe_points) for fc in fcurves(ob)}
    with pytest.raises(RuntimeError, match='fps_out: expected a positive frame rate .* found "abc"'):
        bpy.ops.anim.inbetween_resample_action(fps="abc", only_selected=False)
    assert before == {(fc.data_path, fc.array_index): len(fc.keyframe_points) for fc in fcurves(ob)}
    # A rate it reads: Spine's Y channel is made, on the same 16 keys as its others.
    frames = whole_frames(ob)
    q0, _ = original_channels(ob, frames)
    spine = [pb.name for pb in ob.pose.bones].index("Spine")
    assert bpy.ops.anim.inbetween_resample_action(fps="30", only_selected=False) == {"FINISHED"}
    ys = [fc for fc in fcurves(ob) if fc.data_path == 'pose.bones["Spine"].rotation_euler']
    assert sorted(fc.array_index for fc in ys) == [0, 1, 2]
    assert {len(fc.keyframe_points) for fc in ys} == {16}
    import inbetween

    expected = inbetween.resample(q0[:, spine], "120", "30")
    bpy.context.scene.frame_set(frames[0] + 4 * 7)
    got = np.array(tuple(ob.pose.bones["Spine"].rotation_euler.to_quaternion()))
    assert quat_angles(got, expected[7]) <= 1e-5


def test_action_fcurves_reads_the_legacy_api(extension):
    """Blender 4.2/4.3 (and 4.4's unlayered actions) keep F-curves in ``action.fcurves``: the
    compatibility module reads them there (a stand-in action, whatever Blender runs the test),
    and the imported clip's action, layered from 4.4 on, legacy before."""
    channels = module(extension, "channels")

    class Legacy:
        is_action_layered = False
        fcurves = ["a", "b"]

    class Data:
        class animation_data:
            action = Legacy()

    assert channels.action_fcurves(Data()) == ["a", "b"]
    ob = load_bvh("QUATERNION")
    assert [fc.data_path for fc in channels.action_fcurves(ob)] == [fc.data_path for fc in fcurves(ob)]
    clear()


def test_reduce_keys_on_an_fbx_clip(extension):
    """A clip imported by Blender's FBX importer (quaternion bones, every channel keyed, scale
    channels the operator leaves alone): within 1° at every frame, independently re-evaluated."""
    import addon_utils

    # Blender 5.0.1's FBX importer sets `light.cycles.cast_shadow`, which 5.0's Cycles no longer
    # has: without Cycles registered it skips that line (the clip has a light).
    addon_utils.disable("cycles", default_set=True)
    clear()
    path = os.path.join(ROOT, "fixtures/fbx/real/huesitos.fbx")
    assert bpy.ops.import_scene.fbx(filepath=path) == {"FINISHED"}
    ob = next(o for o in bpy.data.objects if o.type == "ARMATURE")
    bpy.context.view_layer.objects.active = ob
    frames = whole_frames(ob)
    rot0, loc0, _ = pose(ob, frames)
    scales = {fc.data_path: [tuple(k.co) for k in fc.keyframe_points]
              for fc in fcurves(ob) if fc.data_path.endswith(".scale")}
    keys_before = sum(len(fc.keyframe_points) for fc in fcurves(ob))
    assert bpy.ops.anim.inbetween_reduce_keys(tolerance=DEGREE, location_tolerance=LOCATION,
                                              only_selected=False) == {"FINISHED"}
    rot1, loc1, _ = pose(ob, frames)
    err = matrix_angles(rot0, rot1)
    assert err.max() <= DEGREE + FLOAT32_ANGLE, math.degrees(err.max())
    assert np.linalg.norm(loc1 - loc0, axis=-1).max() <= LOCATION + FLOAT32_LENGTH
    assert scales == {fc.data_path: [tuple(k.co) for k in fc.keyframe_points]
                      for fc in fcurves(ob) if fc.data_path.endswith(".scale")}
    keys_after = sum(len(fc.keyframe_points) for fc in fcurves(ob))
    assert keys_after < keys_before
    print(f"\nFIGURES reduce FBX huesitos: {len(frames)} frames x {len(ob.pose.bones)} bones, keys "
          f"{keys_before} -> {keys_after}, worst {math.degrees(err.max()):.4f}°")


def test_reduce_keys_on_an_object_spinning_past_a_turn(extension):
    """An object (not a bone) in Euler XYZ, keyed at every frame, turning twice about Z while it
    nods about X: its angles pass 360° and the keys keep them (the written values are the
    channels' own), within 1° at every frame of its world matrix."""
    clear()
    ob = bpy.data.objects.new("spinner", None)
    bpy.context.scene.collection.objects.link(ob)
    bpy.context.view_layer.objects.active = ob
    ob.rotation_mode = "XYZ"
    frames = list(range(1, 121))
    for f in frames:
        u = (f - 1) / 119
        ob.rotation_euler = (0.4 * math.sin(9 * u), 0.2 * u, 4 * math.pi * u * u)
        ob.location = (math.cos(3 * u), 0.0, 0.5 * u)
        ob.keyframe_insert("rotation_euler", frame=f)
        ob.keyframe_insert("location", frame=f)
    scene = bpy.context.scene

    def world():
        out = np.empty((len(frames), 4, 4))
        for i, f in enumerate(frames):
            scene.frame_set(f)
            out[i] = np.array(ob.matrix_world)
        return out

    m0 = world()
    assert bpy.ops.anim.inbetween_reduce_keys(tolerance=DEGREE, location_tolerance=LOCATION) == {"FINISHED"}
    m1 = world()
    err = matrix_angles(m0[:, :3, :3], m1[:, :3, :3])
    assert err.max() <= DEGREE + FLOAT32_ANGLE, math.degrees(err.max())
    assert np.linalg.norm(m1[:, :3, 3] - m0[:, :3, 3], axis=-1).max() <= LOCATION + FLOAT32_LENGTH
    z = [fc for fc in fcurves(ob) if fc.data_path == "rotation_euler" and fc.array_index == 2][0]
    assert len(z.keyframe_points) < 60 and z.keyframe_points[-1].co[1] == pytest.approx(4 * math.pi, rel=1e-6)
    print(f"\nFIGURES reduce object (Euler XYZ, two turns): 120 frames -> "
          f"{len(z.keyframe_points)} keys, worst {math.degrees(err.max()):.4f}°")


@pytest.mark.parametrize("fps,base,rate", [(30, 1.001, Fraction(30000, 1001)), (24, 1.0, Fraction(24)),
                                           (120, 0.9999960064888, Fraction(120)),
                                           (24, 1.001, Fraction(24000, 1001)), (25, 2.0, Fraction(25, 2)),
                                           (1000, 1.0, Fraction(1000))])
def test_scene_rate_is_exact(extension, fps, base, rate):
    """29.97 is 30/1.001 in Blender; the BVH importer's 120/0.999996 is 120 (the standard rates
    within 1e-4, as inbetween reads a BVH Frame Time); other rates are fps/fps_base."""
    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = fps, base
    assert module(extension, "rates").scene_rate(scene) == rate
