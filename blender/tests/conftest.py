# SPDX-License-Identifier: GPL-3.0-or-later
"""Headless Blender (``bpy`` from PyPI) with the built extension installed into a throw-away user
folder, and the clips the tests run on.

Blender reads ``BLENDER_USER_RESOURCES`` when ``bpy`` is first imported, so it is set here before
anything imports ``bpy``: the extension is installed under a temporary folder, never under
``~/.config/blender``. The zip is ``INBETWEEN_BLENDER_ZIP`` (``.ci/blender.sh`` passes the one
``blender/build.sh`` made), else the newest ``target/blender/inbetween-*.zip``.
"""

import glob
import os
import shutil
import subprocess
import sys
import tempfile

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
USER = tempfile.mkdtemp(prefix="inbetween-blender-")
os.environ["BLENDER_USER_RESOURCES"] = USER

import bpy  # noqa: E402  (after BLENDER_USER_RESOURCES)


def pytest_report_header(config):
    return f"Blender {bpy.app.version_string} (bpy), user resources {USER}"


def _zip():
    z = os.environ.get("INBETWEEN_BLENDER_ZIP")
    if z:
        return os.path.abspath(z)
    found = sorted(glob.glob(os.path.join(ROOT, "target", "blender", "inbetween-*.zip")),
                   key=os.path.getmtime)
    if not found:
        pytest.exit("no extension zip: run blender/build.sh first (or set INBETWEEN_BLENDER_ZIP)")
    return found[-1]


@pytest.fixture(scope="session")
def extension():
    """The installed extension: its package name in ``sys.modules`` (``bl_ext.user_default.inbetween``)."""
    result = bpy.ops.extensions.package_install_files(
        repo="user_default", filepath=_zip(), enable_on_install=True)
    assert result == {"FINISHED"}, result
    yield "bl_ext.user_default.inbetween"
    shutil.rmtree(USER, ignore_errors=True)


@pytest.fixture(scope="session")
def cli():
    """The command line: ``INBETWEEN_BIN``, else the debug build of the workspace; None when
    neither exists (the tests then compare with the Python package alone, and say so)."""
    path = os.environ.get("INBETWEEN_BIN") or os.path.join(ROOT, "target", "debug", "inbetween")
    if not os.path.exists(path):
        if os.environ.get("INBETWEEN_REQUIRE_CLI"):
            pytest.fail(f"INBETWEEN_REQUIRE_CLI is set but there is no command line at {path}")
        return None
    return path


def run_cli(cli, *args):
    out = subprocess.run([cli, *args], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return out


def clear():
    """An empty file (objects, armatures and actions removed; preferences and the installed
    extension kept, which ``read_factory_settings`` would reset)."""
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob)
    for a in list(bpy.data.armatures):
        bpy.data.armatures.remove(a)
    for a in list(bpy.data.actions):
        bpy.data.actions.remove(a)


def load_bvh(rotate_mode, path="fixtures/bvh/cmu_01_01.bvh"):
    """Import a BVH clip with Blender's importer (the scene's rate set from its Frame Time);
    returns the armature."""
    clear()
    r = bpy.ops.import_anim.bvh(filepath=os.path.join(ROOT, path), rotate_mode=rotate_mode,
                                update_scene_fps=True, update_scene_duration=True)
    assert r == {"FINISHED"}
    return bpy.context.active_object
