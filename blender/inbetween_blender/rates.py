# SPDX-License-Identifier: GPL-3.0-or-later
"""The scene's frame rate as an exact rate.

Blender's rate is ``render.fps / render.fps_base`` with ``fps_base`` a float: 29.97 is
``fps = 30, fps_base = 1.001``, and the BVH importer sets ``fps_base = 0.999996`` for a
``Frame Time: .0083333`` (120.00048 fps). The rate used here is the nearest standard rate (the
list of docs/spec.md § BVH: 12, 15, 24, 25, 30, 48, 50, 60, 90, 100, 120, 240 and their /1001
ratios) within 1e-4 relative, as ``inbetween`` reads a BVH ``Frame Time``; else ``fps/fps_base``
with ``fps_base`` as the fraction nearest it with a denominator up to 10 000.
"""

from __future__ import annotations

from fractions import Fraction

STANDARD = [Fraction(n) for n in (12, 15, 24, 25, 30, 48, 50, 60, 90, 100, 120, 240)]
STANDARD += [r * Fraction(1000, 1001) for r in list(STANDARD)]


def scene_rate(scene) -> Fraction:
    """The scene's frames per second, exactly (see the module's doc)."""
    fps = Fraction(scene.render.fps) / Fraction(scene.render.fps_base).limit_denominator(10000)
    for r in STANDARD:
        if abs(fps - r) <= r * Fraction(1, 10000):
            return r
    return fps


def as_text(rate: Fraction) -> str:
    """A rate as ``inbetween`` takes it: ``"120"``, ``"30000/1001"``."""
    return str(rate.numerator) if rate.denominator == 1 else f"{rate.numerator}/{rate.denominator}"

