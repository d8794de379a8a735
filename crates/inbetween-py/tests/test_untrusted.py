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
