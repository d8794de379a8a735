# SPDX-License-Identifier: GPL-3.0-or-later
"""Reduce keys: the fewest keys of each bone's rotation and location channels that Blender plays
back within a tolerance at every frame, verified in Blender's own evaluation.

For each target (pose bone, or the object): its channels are sampled at every whole frame of the
action (``FCurve.evaluate``), the rotation made as Blender's pose evaluation makes it, and
``inbetween.reduce(..., scheme="nlerp")`` chooses the key frames (nlerp is how Blender plays
``LINEAR`` quaternion keys; the location within ``location_tolerance`` by lerp, as ``LINEAR``
plays it). The keys are written as ``LINEAR`` keyframes holding the channels' own values at those
frames (quaternion keys each in the previous key's hemisphere), the written F-curves are evaluated
again at every frame and played as Blender plays them — quaternion components lerped then
normalised, Euler channels lerped each on its own — and compared with the original rotation and
location. Where a target misses (an Euler bone's per-channel lerp is not nlerp), its tolerance
for ``inbetween.reduce`` is halved and it is reduced again; after ``MAX_ROUNDS`` every frame is
kept. With a position tolerance, the heads and tails of every bone are then compared in the
armature's space at every frame, evaluated by Blender (``scene.frame_set``), and the bone that
moves a missing point most is tightened the same way (``world_pass``), until every point is
within.
"""

from __future__ import annotations

import time
from typing import Dict, List, Optional

import numpy as np

from . import playback
from .channels import QUATERNION, Target

#: Halvings of a target's tolerance before every frame becomes a key.
MAX_ROUNDS = 12
#: Below this angle (rad) every frame becomes a key too: ``inbetween.reduce`` refuses
#: tolerances under 1e-9 rad (what it can verify), and float32 keys play no closer.
MIN_ANGLE = 1e-8


class TargetReduction:
    """One target's reduction: its frames as Blender played them before, its current
    tolerances for ``inbetween.reduce``, the keys written and the errors measured."""

    def __init__(self, target: Target, frames: np.ndarray, rate: str, angle_tol: float,
                 location_tol: float):
        self.target = target
        self.frames = frames
        self.rate = rate
        self.angle_tol = angle_tol
        self.location_tol = location_tol
        self.rotation_values = playback.sample(target.rotation, target.rest_rotation, frames)
        self.location_values = playback.sample(target.location, target.rest_location, frames)
        self.reference = playback.rotations(target.mode, self.rotation_values)
        self.keys_before = sum(len(fc.keyframe_points) for fc in target.fcurves())
        # What inbetween.reduce is asked for (tightened where Blender's playback misses).
        self.reduce_angle = angle_tol
        self.reduce_location = location_tol
        self.rounds = 0
        self.keys: Optional[np.ndarray] = None
        self.angle_error = 0.0
        self.location_error = 0.0
        self.every_frame = False

    def run(self) -> None:
        """Reduce, write, play back; tighten and redo until this target is within its own
        tolerances (angle and location)."""
        import inbetween

        while True:
            self.rounds += 1
            if self.rounds > MAX_ROUNDS or self.reduce_angle < MIN_ANGLE:
                self.every_frame = True
                self._write(np.arange(len(self.frames)))
                self._measure()
                return
            kwargs = {}
            if self.target.has_location:
                kwargs = {"translations": self.location_values,
                          "translation_tolerance": self.reduce_location}
            r = inbetween.reduce(self.reference, self.rate, self.reduce_angle, degrees=False,
                                 scheme="nlerp", velocities=False, **kwargs)
            self._write(np.asarray(r.keys[0]))
            self._measure()
            rot_ok = self.angle_error <= self.angle_tol
            loc_ok = self.location_error <= self.location_tol
            if rot_ok and loc_ok:
                return
            if not rot_ok:
                self.reduce_angle *= 0.5
            if not loc_ok:
                self.reduce_location *= 0.5

    def tighten(self) -> None:
        """Halve both tolerances (a world-space point below this target missed) and run again."""
        self.reduce_angle *= 0.5
        self.reduce_location *= 0.5
        self.run()

    def _write(self, keys: np.ndarray) -> None:
        self.keys = keys
        t = self.target
        at = self.frames[keys]
        rot = self.rotation_values[keys]
        if t.mode == QUATERNION and all(fc is not None for fc in t.rotation):
            # Each key in the previous key's hemisphere, as nlerp plays them (a sign can only be
            # flipped when all four channels are written; else the values stay as they were).
            rot = playback.hemisphere_continuous(rot)
        for i, fc in enumerate(t.rotation):
            if fc is not None:
                playback.write_linear(fc, at, rot[:, i])
        for i, fc in enumerate(t.location):
            if fc is not None:
                playback.write_linear(fc, at, self.location_values[keys, i])

    def _measure(self) -> None:
        """The largest angle and location errors of the written F-curves as Blender plays them,
        at every frame."""
        t = self.target
        played = playback.sample(t.rotation, t.rest_rotation, self.frames)
        q = playback.rotations(t.mode, played)
        self.angle_errors = playback.angles(self.reference, q)
        self.angle_error = float(self.angle_errors.max())
        loc = playback.sample(t.location, t.rest_location, self.frames)
        self.location_errors = np.linalg.norm(loc - self.location_values, axis=1)
        self.location_error = float(self.location_errors.max())

    @property
    def keys_after(self) -> int:
        return sum(len(fc.keyframe_points) for fc in self.target.fcurves())


def pose_points(obj, scene, frames: np.ndarray, shell: float = 0.0) -> np.ndarray:
    """(T, B, P, 3): points of every pose bone in the armature's space at each frame, as Blender
    evaluates the scene there (``scene.frame_set``: the action, constraints, drivers): its head
    and tail (P = 2), and with a ``shell`` distance the three points at that distance along the
    bone's own x, y and z axes from its head (P = 5; a twist about the bone moves them, not the
    tail)."""
    bones = list(obj.pose.bones)
    out = np.empty((len(frames), len(bones), 5 if shell > 0 else 2, 3))
    axes = np.eye(3) * shell
    for i, f in enumerate(frames):
        scene.frame_set(int(f))
        for b, pb in enumerate(bones):
            out[i, b, 0] = pb.head
            out[i, b, 1] = pb.tail
            if shell > 0:
                m = np.array(pb.matrix)
                out[i, b, 2:] = m[:3, 3] + axes @ m[:3, :3].T
    return out


def world_pass(obj, scene, frames, reference, by_bone: Dict[str, TargetReduction],
               position_tol: float, shell: float) -> tuple:
    """Tighten reduced bones until every point of :func:`pose_points` is within ``position_tol``
    of ``reference`` at every frame. For each point that misses at a frame, the bone of its chain
    that moves it most there is tightened: rotation error θ at that frame moving the point by
    2·sin(θ/2)·(its distance from the bone's head), plus the bone's location error (a bone's own
    rotation does not move its head). After ``2·MAX_ROUNDS`` rounds every reduced bone on the
    chain of a point that misses is tightened at once, for at most ``MAX_ROUNDS`` more (by then
    those bones keep every frame, and their points are where they were).
    Returns (largest displacement, rounds)."""
    bones = list(obj.pose.bones)
    index = {pb.name: i for i, pb in enumerate(bones)}
    chains = []
    for pb in bones:
        chain, p = [], pb
        while p is not None:
            if p.name in by_bone:
                chain.append(by_bone[p.name])
            p = p.parent
        chains.append(chain)
    worst, rounds = 0.0, 0
    for rounds in range(1, 3 * MAX_ROUNDS + 2):
        played = pose_points(obj, scene, frames, shell)
        d = np.linalg.norm(played - reference, axis=-1)  # (T, B, P): head, tail, shell
        worst = float(d.max()) if d.size else 0.0
        if worst <= position_tol or rounds > 3 * MAX_ROUNDS:
            break
        chosen = {}
        for b, end in zip(*np.nonzero(np.any(d > position_tol, axis=0))):
            chain = chains[b]
            if rounds > 2 * MAX_ROUNDS:
                chosen.update((r.target.name, r) for r in chain)
                continue
            if not chain:
                continue
            missed = d[:, b, end] > position_tol
            moved = np.stack([_moves(r, index[r.target.name], b, end, reference) for r in chain])
            for i in np.unique(np.argmax(moved[:, missed], axis=0)):
                chosen[chain[i].target.name] = chain[i]
        if not chosen:
            break  # the points that miss are moved by no reduced bone
        for r in chosen.values():
            r.tighten()
    return worst, rounds


def _moves(r: TargetReduction, c: int, b: int, end: int, reference: np.ndarray) -> np.ndarray:
    """(T,) how far bone ``c``'s errors (reduction ``r``) move point ``end`` (0 head, 1 tail,
    2-4 shell) of bone ``b`` at each frame: its location error, plus 2·sin(θ/2)·arm for its
    rotation error θ, arm the point's distance from bone ``c``'s head (none for a bone's own
    head)."""
    m = np.array(r.location_errors)
    if not (c == b and end == 0):
        arm = np.linalg.norm(reference[:, b, end] - reference[:, c, 0], axis=-1)
        m = m + 2.0 * np.sin(r.angle_errors / 2.0) * arm
    return m


def reduce_object(obj, scene, targets: List[Target], rate: str, angle_tol: float,
                  location_tol: float, position_tol: float, shell: float = 0.0) -> dict:
    """Reduce every target of ``obj``; returns the per-target reductions and the figures."""
    start = time.perf_counter()
    f0, f1 = playback.frame_range([fc for t in targets for fc in t.fcurves()])
    frames = np.arange(f0, f1 + 1, dtype=np.float64)
    world = position_tol > 0 and obj.type == "ARMATURE"
    current = scene.frame_current, scene.frame_subframe
    worst_point, world_rounds = None, 0
    try:
        reference_points = pose_points(obj, scene, frames, shell) if world else None
        reductions = [TargetReduction(t, frames, rate, angle_tol, location_tol) for t in targets]
        for r in reductions:
            r.run()
        if world:
            by_bone = {r.target.name: r for r in reductions}
            worst_point, world_rounds = world_pass(obj, scene, frames, reference_points, by_bone,
                                                   position_tol, shell)
    finally:
        if world:
            scene.frame_set(current[0], subframe=current[1])
    return {
        "reductions": reductions,
        "frames": (f0, f1),
        "seconds": time.perf_counter() - start,
        "worst_point": worst_point,
        "world_rounds": world_rounds,
    }


def table(result: dict, location: bool) -> str:
    """The printed report: one row per target."""
    rows = [f"{'bone':<24} {'mode':<10} {'keys before':>11} {'after':>7} {'max error °':>11}"
            + (f" {'max loc err':>11}" if location else "") + "  note"]
    for r in result["reductions"]:
        note = "every frame kept" if r.every_frame else (
            f"tightened to {np.degrees(r.reduce_angle):.4g}°" if r.reduce_angle < r.angle_tol else "")
        row = (f"{r.target.name:<24} {r.target.mode:<10} {r.keys_before:>11} {r.keys_after:>7} "
               f"{np.degrees(r.angle_error):>11.4f}")
        if location:
            row += f" {r.location_error:>11.3g}" if r.target.has_location else f" {'':>11}"
        rows.append(row + "  " + note)
    return "\n".join(rows)
