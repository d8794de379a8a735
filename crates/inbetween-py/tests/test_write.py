"""`inbetween.write`: keys documents and BVH, the bytes the command line writes."""

import os
import stat
import subprocess

import numpy as np
import pytest

import inbetween
from conftest import FIXTURES, angle


def test_bvh_on_its_skeleton_is_what_convert_writes(cli, tmp_path):
    src = FIXTURES / "bvh" / "cmu_01_01.bvh"
    ours = tmp_path / "ours.bvh"
    inbetween.write(ours, inbetween.read(src))
    keys, theirs = tmp_path / "keys.json", tmp_path / "theirs.bvh"
    subprocess.run([cli, "convert", str(src), "-o", str(keys)], check=True)
    subprocess.run([cli, "convert", str(keys), "--skeleton", str(src), "-o", str(theirs)],
                   check=True)
    assert ours.read_bytes() == theirs.read_bytes()
    back = inbetween.read(ours)
    assert np.max(angle(back.rotations, inbetween.read(src).rotations)) < 1e-6


@pytest.mark.parametrize("ext", ["csv", "json"])
@pytest.mark.parametrize("name", ["gltf/real/RiggedSimple.gltf", "bvh/cmu_01_01.bvh",
                                  "interp/multitrack.json"])
def test_keys_read_back_to_the_same_numbers(tmp_path, ext, name):
    clip = inbetween.read(FIXTURES / name)
    out = tmp_path / f"keys.{ext}"
    inbetween.write(out, clip)
    back = inbetween.read(out)
    assert back.names == clip.names
    for (t0, q0, p0), (t1, q1, p1) in zip(clip.tracks, back.tracks):
        assert np.array_equal(t0, t1)
        # The reader normalises every quaternion it reads: the last bit may move (2.2e-16).
        assert np.max(np.abs(q0 - q1)) <= 4.5e-16
        assert (p0 is None and p1 is None) or np.array_equal(p0, p1)


def test_arrays_in_euler_angles_with_few_digits(tmp_path):
    t = np.arange(5) / 24
    a = np.radians(30) * np.arange(5)
    q = np.stack([np.cos(a / 2), 0 * a, 0 * a, np.sin(a / 2)], axis=1)
    out = tmp_path / "spin.csv"
    inbetween.write(out, inbetween.Clip.from_arrays(t, q, names=["wheel"]), to="euler:ZYX",
                    precision=3)
    lines = out.read_text().splitlines()
    assert lines[0] == "track,time,e1,e2,e3"
    assert lines[2] == f"wheel,{1 / 24!r},30.000,0.000,0.000"


@pytest.mark.parametrize(
    "call, says",
    [
        (lambda d: inbetween.write(d / "x.glb", inbetween.read(FIXTURES / "convert" / "two_tracks.csv")), "path:"),
        (lambda d: inbetween.write(d / "x.txt", inbetween.read(FIXTURES / "convert" / "two_tracks.csv")), "write takes .csv, .json, .npy, .npz, .bvh, .glb or .gltf"),
        (lambda d: inbetween.write(d / "x.bvh", inbetween.read(FIXTURES / "convert" / "two_tracks.csv")), "skeleton: BVH output is written on a skeleton"),
        (lambda d: inbetween.write(d / "x.csv", inbetween.read(FIXTURES / "convert" / "two_tracks.csv"), to="euler:QQQ"), "to:"),
        (lambda d: inbetween.write(d / "x.bvh", inbetween.read(FIXTURES / "convert" / "two_tracks.csv"), skeleton=FIXTURES / "bvh" / "cmu_01_01.bvh"), "skeleton"),
    ],
)
def test_errors_write_nothing(tmp_path, call, says):
    with pytest.raises(inbetween.InputError) as e:
        call(tmp_path)
    assert says in str(e.value), str(e.value)
    assert "--" not in str(e.value) and " -o " not in str(e.value), "no command-line flag"
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("ext", ["npz", "npy"])
def test_frames_are_the_arrays_interp_writes(cli, tmp_path, ext):
    # A BVH clip at its own rate: interp's frames are its frames, so the files are equal.
    src = FIXTURES / "bvh" / "cmu_01_01.bvh"
    ours, theirs = tmp_path / f"ours.{ext}", tmp_path / f"theirs.{ext}"
    inbetween.write(ours, inbetween.read(src))
    subprocess.run([cli, "interp", str(src), "-o", str(theirs)], check=True)
    assert ours.read_bytes() == theirs.read_bytes()
    if ext == "npz":
        z = np.load(ours)
        assert z["rotations"].shape == (61, 31, 4) and str(z["fps"]) == "120"


def test_npz_needs_one_grid_and_a_rate(tmp_path):
    multi = inbetween.read(FIXTURES / "interp" / "multitrack.json")
    with pytest.raises(inbetween.InputError) as e:
        inbetween.write(tmp_path / "x.npz", multi)
    assert "npz holds every track on the same frames" in str(e.value)
    t = np.array([0.0, 0.1])
    with pytest.raises(inbetween.InputError) as e:
        inbetween.write(tmp_path / "y.npz", inbetween.Clip.from_arrays(t, [[1, 0, 0, 0]] * 2))
    assert "fps: npy and npz hold frames" in str(e.value)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.skipif(os.name != "posix", reason="file modes")
@pytest.mark.parametrize("ext", ["csv", "glb"])
def test_a_new_file_gets_the_usual_mode_and_a_replaced_one_keeps_its_own(tmp_path, ext):
    # 0666 less the umask, as the command line's output (not the temporary file's 0600).
    umask = os.umask(0)
    os.umask(umask)
    clip = inbetween.read(FIXTURES / "gltf" / "real" / "RiggedSimple.gltf")
    out = tmp_path / f"out.{ext}"
    inbetween.write(out, clip)
    assert stat.S_IMODE(out.stat().st_mode) == 0o666 & ~umask
    out.chmod(0o640)
    inbetween.write(out, clip)
    assert stat.S_IMODE(out.stat().st_mode) == 0o640


def test_write_goes_through_the_command_lines_output(tmp_path):
    """A link stays and its target is replaced, as `-o` does; a folder and a missing folder are
    input errors naming the path; nothing is left behind."""
    clip = inbetween.Clip.from_arrays([0.0, 1.0], [[1, 0, 0, 0], [0, 1, 0, 0]])
    target = tmp_path / "target.csv"
    target.write_text("old\n")
    link = tmp_path / "link.csv"
    link.symlink_to("target.csv")
    inbetween.write(link, clip)
    assert link.is_symlink()
    assert target.read_text().startswith("track,time,w,x,y,z\n")
    (tmp_path / "folder.csv").mkdir()
    with pytest.raises(inbetween.InputError, match="folder.csv: expected a file, found a directory"):
        inbetween.write(tmp_path / "folder.csv", clip)
    with pytest.raises(inbetween.InputError, match="directory .*missing does not exist"):
        inbetween.write(tmp_path / "missing" / "x.csv", clip)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["folder.csv", "link.csv", "target.csv"]


def test_write_refuses_what_it_cannot_write_rather_than_writing_csv(tmp_path):
    """`.usda` (not written from Python) was CSV text under a USD name."""
    clip = inbetween.Clip.from_arrays([0.0, 1.0], [[1, 0, 0, 0], [0, 1, 0, 0]])
    for name in ("x.usda", "x.fbx", "x.txt"):
        with pytest.raises(inbetween.InputError, match="write takes .csv, .json"):
            inbetween.write(tmp_path / name, clip)
    assert list(tmp_path.iterdir()) == []


def test_a_write_the_system_refuses_is_an_os_error(tmp_path):
    """A FIFO whose reader goes away: the writer's broken pipe is Python's BrokenPipeError (an
    OSError) naming the path, not an InputError: the input was fine."""
    import threading
    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)

    def read_then_leave():
        # Opening waits for the writer; one byte read, the reader leaves with megabytes unread.
        with open(fifo, "rb") as f:
            f.read(1)

    reader = threading.Thread(target=read_then_leave)
    reader.start()
    n = 200_000  # rows enough to fill the pipe before the reader leaves
    t = np.arange(n) / 30.0
    q = np.tile([[1.0, 0, 0, 0]], (n, 1))
    with pytest.raises(BrokenPipeError, match="pipe.csv: cannot write"):
        inbetween.write(fifo, inbetween.Clip.from_arrays(t, q))
    reader.join()
