"""Hostile calls from Python: grids too large to hold, paths that look like flags, options
that are not the command's. Each is a Python exception or a record, never an abort of the
interpreter (the cases that aborted it run in a subprocess, so a regression fails this test
instead of ending pytest)."""

import pathlib
import shutil
import subprocess
import sys

import numpy as np
import pytest

import inbetween

ROOT = pathlib.Path(__file__).resolve().parents[3]
FIXTURES = ROOT / "fixtures"


def _in_subprocess(code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120)


@pytest.mark.parametrize("call", [
    "inbetween.frame_times(10**9, 1, 1000)",
    "inbetween.frame_times(10**7, 30, 30000)",
    "inbetween.resample(np.tile([1.0, 0, 0, 0], (2, 1)), 1e-3, 1e6)",
    "inbetween.resample(np.tile([1.0, 0, 0, 0], (3, 50000, 1)), 1, 2000)",
])
def test_a_grid_too_large_is_a_value_error_not_an_abort(call):
    code = ("import numpy as np, inbetween\n"
            "try:\n"
            f"    {call}\n"
            "    print('NO ERROR')\n"
            "except ValueError as e:\n"
            "    print('ValueError:', e)\n")
    r = _in_subprocess(code)
    assert r.returncode == 0, (r.returncode, r.stderr[-2000:])
    assert r.stdout.startswith("ValueError:"), r.stdout
    assert "numbers (2 GiB of float64) a result may hold" in r.stdout, r.stdout


def test_a_grid_beyond_the_clock_is_a_value_error():
    with pytest.raises(ValueError, match="beyond what the frame clock supports"):
        inbetween.frame_times(10**15, 1, 10**6)


def test_grids_within_the_bound_are_made():
    t = inbetween.frame_times(31, 30, 60)
    assert len(t) == 61 and t[-1] == 1.0
    out = inbetween.resample(np.tile([1.0, 0, 0, 0], (3, 2, 1)), 1, 10)
    assert out.shape == (21, 2, 4)


def test_paths_that_look_like_flags_are_paths(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    shutil.copy(FIXTURES / "bvh/mixed_orders.bvh", tmp_path / "--help")
    r = inbetween.process_file("--help", "-", "convert")
    assert r["status"] == "ok", r
    # The output was the file "-", not standard output.
    assert (tmp_path / "-").read_text().startswith("HIERARCHY")
    missing = inbetween.process_file("--version", "out.json", "convert")
    assert missing["status"] == "failed" and missing["exit_code"] == 2, missing
    assert "--version" in missing["error"], missing


def test_unknown_and_batch_options_are_type_errors(tmp_path):
    clip = FIXTURES / "bvh/mixed_orders.bvh"
    with pytest.raises(TypeError, match='"frob" is not an option of convert'):
        inbetween.process_file(clip, tmp_path / "a.json", "convert", frob=1)
    with pytest.raises(TypeError, match="a batch's own option"):
        inbetween.process_file(clip, tmp_path / "a.json", "convert", out_dir=str(tmp_path))
    with pytest.raises(TypeError, match="not an option of interp"):
        inbetween.process_file(clip, tmp_path / "a.bvh", "interp", tolerance=1)
    assert not (tmp_path / "a.json").exists()
    # A value that starts with "-" is a value: refused as a rate, never read as a flag.
    r = inbetween.process_file(clip, tmp_path / "b.bvh", "interp", fps="-24")
    assert r["status"] == "failed" and "--fps" in r["error"], r
    assert r["error"].startswith("invalid value '-24' for '--fps': "), r


def test_options_that_need_others_are_refused_as_the_command_line_refuses_them(tmp_path):
    """The command line's parser refuses these before running; a request by keyword meets the
    same rules in the library (exit 2, nothing written)."""
    clip = FIXTURES / "bvh/mixed_orders.bvh"
    out = tmp_path / "k.json"
    for options, message in [
        ({}, "reduce needs --tolerance or --position-tolerance"),
        ({"tolerance": 1, "shell": 2}, "--shell needs --position-tolerance"),
        ({"tolerance": 1, "joint_tolerance": ["Hips=0.1"]},
         "--joint-tolerance needs --position-tolerance"),
    ]:
        r = inbetween.process_file(clip, out, "reduce", **options)
        assert (r["status"], r["exit_code"], r["error"]) == ("failed", 2, message), r
        assert not out.exists()


def test_deep_usd_is_an_input_error_in_python(tmp_path):
    deep = tmp_path / "deep.usda"
    deep.write_text("#usda 1.0\n" + 'def "a" {\n' * 5000 + "}\n" * 5000)
    code = ("import inbetween\n"
            "try:\n"
            f"    inbetween.read({str(deep)!r})\n"
            "except ValueError as e:\n"
            "    print('ValueError:', e)\n")
    r = _in_subprocess(code)
    assert r.returncode == 0, (r.returncode, r.stderr[-2000:])
    assert "nested deeper than 256 levels" in r.stdout, r.stdout


@pytest.mark.parametrize("call, message", [
    (lambda c: c(0.5, order=-1), r"order: expected 0 \(rotation\)"),
    (lambda c: c(0.5, order=2**70), r"order: expected 0 \(rotation\)"),
    (lambda c: inbetween.frame_times(-1, 30, 30), "n: expected at least one frame, found -1"),
    (lambda c: inbetween.frame_times(2**70, 30, 30), "n: expected at least one frame and at most"),
    (lambda c: inbetween.Curve([0, 1j], [[1, 0, 0, 0], [1, 0, 0, 0]]), "times: expected real"),
])
def test_integers_out_of_range_are_input_errors_not_overflow(call, message):
    curve = inbetween.Curve([0.0, 1.0], [[1, 0, 0, 0], [0, 1, 0, 0]])
    with pytest.raises(inbetween.InputError, match=message):
        call(curve)


def test_negative_precision_is_an_input_error(tmp_path):
    clip = inbetween.Clip.from_arrays([0.0, 1.0], [[1, 0, 0, 0], [0, 1, 0, 0]])
    with pytest.raises(inbetween.InputError, match="precision: expected 0 to 17 digits"):
        inbetween.write(tmp_path / "x.csv", clip, precision=-1)
    assert not (tmp_path / "x.csv").exists()


def test_a_reduction_refuses_frames_of_another_shape():
    q = np.tile([[1.0, 0, 0, 0], [0.0, 1, 0, 0]], (10, 1))
    r = inbetween.reduce(q, 30, 1)
    with pytest.raises(inbetween.InputError, match=r"rotations: expected .* \(20, 4\)"):
        r.curve(q[:2])
    with pytest.raises(inbetween.InputError, match="joint: expected None"):
        r.key_times(5)
    joints = inbetween.reduce(np.stack([q, q], axis=1), 30, 1)
    with pytest.raises(inbetween.InputError, match="joint: expected a joint index"):
        joints.key_times()


def test_process_file_never_writes_over_its_input(tmp_path):
    src = tmp_path / "keys.csv"
    src.write_text("time,w,x,y,z\n0,1,0,0,0\n1,0,1,0,0\n")
    before = src.read_bytes()
    link = tmp_path / "link.csv"
    link.symlink_to("keys.csv")
    for out in (src, link):
        r = inbetween.process_file(src, out, "convert")
        assert r["status"] == "failed" and r["exit_code"] == 2, r
        assert "which the command reads" in r["error"], r
        assert src.read_bytes() == before
    # An output path that is a folder is no output to be up to date: a failure, not a skip.
    r = inbetween.process_file(src, tmp_path, "interp", fps=30)
    assert r["status"] == "failed" and "directory" in r["error"], r


def test_binary_usd_reads_as_its_text_and_damage_is_a_value_error(tmp_path):
    """`.usdc`/`.usdz` through the shared reader: the `.usda` twin's tracks; a damaged crate (an
    openusd panic or a refused claim inside) a ValueError naming the file, never an abort."""
    text = inbetween.read(FIXTURES / "usd" / "skel_ntsc.usda")
    for twin in ("skel_ntsc.usdc", "skel_ntsc.usdz"):
        clip = inbetween.read(FIXTURES / "usd" / twin)
        assert clip.names == text.names and clip.fps == text.fps, twin
        for (t1, q1, p1), (t2, q2, p2) in zip(clip.tracks, text.tracks):
            assert np.array_equal(t1, t2) and np.array_equal(q1, q2) and np.array_equal(p1, p2)
    good = (FIXTURES / "usd" / "skel_ntsc.usdc").read_bytes()
    code = "import inbetween\n"
    for k in range(0, len(good), 97):
        cut = tmp_path / f"cut{k}.usdc"
        cut.write_bytes(good[:k])
        code += (f"try:\n    inbetween.read({str(cut)!r})\n"
                 "except ValueError as e:\n    print('ValueError:', e)\n")
    r = _in_subprocess(code)
    assert r.returncode == 0, (r.returncode, r.stderr[-2000:])
    assert r.stdout.count("ValueError:") == len(range(0, len(good), 97)), r.stdout
    assert "cut97.usdc" in r.stdout
