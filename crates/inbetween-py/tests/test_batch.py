"""process_file and the Dask example (examples/python/dask_batch.py): the same outputs, byte
for byte, as the command line's own batch (`--out-dir`), and records like its manifest."""

import os
import pathlib
import shutil
import subprocess
import sys

import pytest

import inbetween

ROOT = pathlib.Path(__file__).resolve().parents[3]
FIXTURES = ROOT / "fixtures"


def _library(folder: pathlib.Path) -> pathlib.Path:
    clips = folder / "clips"
    (clips / "fbx").mkdir(parents=True)
    shutil.copy(FIXTURES / "bvh/cmu_01_01.bvh", clips / "walk.bvh")
    shutil.copy(FIXTURES / "bvh/mixed_orders.bvh", clips / "mixed.bvh")
    shutil.copy(FIXTURES / "fbx/real/huesitos.fbx", clips / "fbx/huesitos.fbx")
    shutil.copy(FIXTURES / "interp/multitrack.json", clips / "keys.json")
    return clips


def _tree(folder: pathlib.Path) -> dict:
    return {p.relative_to(folder).as_posix(): p.read_bytes()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def test_process_file_writes_what_the_command_line_writes(tmp_path, cli):
    clip = FIXTURES / "bvh/cmu_01_01.bvh"
    out = tmp_path / "deep/a.json"
    record = inbetween.process_file(clip, out, "reduce", tolerance=0.5, translation_tolerance=0.1)
    assert record["status"] == "ok" and record["exit_code"] == 0, record
    single = tmp_path / "b.json"
    subprocess.run([cli, "reduce", str(clip), "--tolerance", "0.5", "--translation-tolerance",
                    "0.1", "-o", str(single)], check=True)
    assert out.read_bytes() == single.read_bytes()
    # Newer output: skipped; refresh: done again.
    assert inbetween.process_file(clip, out, "reduce", tolerance=0.5,
                                  translation_tolerance=0.1)["status"] == "skipped"
    assert inbetween.process_file(clip, out, "reduce", refresh=True, tolerance=0.5,
                                  translation_tolerance=0.1)["status"] == "ok"
    # A refused input is a record with the command line's located message and exit code 2.
    bad = tmp_path / "bad.bvh"
    bad.write_text("HIERARCHY\nROOT x\n{\n")
    r = inbetween.process_file(bad, tmp_path / "bad.json", "interp", fps=30)
    assert r["status"] == "failed" and r["exit_code"] == 2
    assert r["error"] == f'{bad}: expected "OFFSET", found the end of the file'
    assert not (tmp_path / "bad.json").exists()
    with pytest.raises(inbetween.InputError, match="command"):
        inbetween.process_file(clip, out, "plot")


def test_process_file_refuses_an_output_named_for_a_format_not_written(tmp_path, cli):
    """`x.usdc` held the input's format with status "ok"; now refused before its folder is made
    or a newer file of that name skips it; with `output_format` it is written. (`x.fbx` was
    refused alike until issue 50, which writes FBX.)"""
    clip = FIXTURES / "bvh/cmu_01_01.bvh"
    newer = tmp_path / "old.usdc"
    newer.write_text("")
    for out, says in ((tmp_path / "new/x.usdc", "USD is written as text only"),
                      (newer, "USD is written"),
                      (tmp_path / "x.USDZ", "USD is written as text only")):
        r = inbetween.process_file(clip, out, "interp", fps=30)
        assert r["status"] == "failed" and r["exit_code"] == 2, r
        assert r["error"].startswith(f"{out}: {says}"), r["error"]
    assert not (tmp_path / "new").exists() and newer.read_text() == ""
    assert not (tmp_path / "x.USDZ").exists()
    r = inbetween.process_file(clip, tmp_path / "y.usdc", "interp", fps=30, output_format="csv")
    assert r["status"] == "ok", r
    csv = subprocess.run([cli, "interp", str(clip), "--fps", "30", "--output-format", "csv"],
                         check=True, capture_output=True).stdout
    assert (tmp_path / "y.usdc").read_bytes() == csv
    # FBX is written: the same bytes as the command line's.
    r = inbetween.process_file(clip, tmp_path / "z.fbx", "interp", fps=30)
    assert r["status"] == "ok", r
    subprocess.run([cli, "interp", str(clip), "--fps", "30", "-o", str(tmp_path / "cli.fbx")],
                   check=True)
    assert (tmp_path / "z.fbx").read_bytes() == (tmp_path / "cli.fbx").read_bytes()


def test_the_dask_example_matches_the_command_lines_batch(tmp_path, cli):
    try:
        import dask.distributed  # noqa: F401
    except ImportError:
        if os.environ.get("INBETWEEN_REQUIRE_CLI"):
            raise
        pytest.skip("dask.distributed is not installed")
    clips = _library(tmp_path)
    options = ["--fps", "30", "--output-format", "json"]
    subprocess.run([cli, "interp", str(clips), *options, "--jobs", "2", "--out-dir",
                    str(tmp_path / "cli")], check=True)
    done = subprocess.run(
        [sys.executable, str(ROOT / "examples/python/dask_batch.py"), str(clips),
         str(tmp_path / "dask"), "--command", "interp", "--workers", "2", "--manifest",
         str(tmp_path / "m.jsonl"), "--", *options],
        capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    cli_tree, dask_tree = _tree(tmp_path / "cli"), _tree(tmp_path / "dask")
    assert sorted(cli_tree) == ["fbx/huesitos.json", "keys.json", "mixed.json", "walk.json"]
    assert dask_tree == cli_tree
    lines = (tmp_path / "m.jsonl").read_text().splitlines()
    assert len(lines) == 4 and all('"status": "ok"' in l for l in lines)


@pytest.mark.parametrize("command, options", [
    ("interp", {"fps": 24}),
    ("convert", {}),
    ("reduce", {"tolerance": 0.5, "translation_tolerance": 0.1}),
    ("reduce", {"position_tolerance": 0.5}),
])
def test_the_record_is_the_manifest_line(tmp_path, cli, command, options):
    """One type makes both: every field of the command line's manifest line (frames, tracks,
    keys, largest error, an error's text) is in process_file's record with the same value."""
    import json
    clips = _library(tmp_path)
    (clips / "broken.bvh").write_text("HIERARCHY\nROOT a\n{\n")
    flags = []
    for k, v in options.items():
        flags += [f"--{k.replace('_', '-')}", str(v)]
    manifest = tmp_path / "manifest.jsonl"
    subprocess.run([cli, command, str(clips), "--out-dir", str(tmp_path / "cli"),
                    "--manifest", str(manifest), *flags], capture_output=True)
    lines = [json.loads(l) for l in manifest.read_text().splitlines()]
    assert len(lines) == 5 and {l["status"] for l in lines} >= {"ok", "failed"}, lines
    for line in lines:
        out = pathlib.Path(line["output"] or tmp_path / "none.json")
        record = inbetween.process_file(line["input"], out, command, refresh=True, **options)
        assert record.pop("exit_code") in ((0,) if line["status"] == "ok" else (1, 2))
        assert isinstance(record.pop("warnings"), list)
        assert record.pop("reports") == []
        record.pop("seconds"), line.pop("seconds")
        if line["output"] is None:  # a planned failure has no output; process_file names its own
            record["output"] = None
        assert record == line
        if line["status"] == "ok":
            assert {"frames", "tracks"} <= set(record), record


def test_reports_are_handed_back_not_printed(tmp_path, capfd):
    """`verbose=True` asks for the -v lines: the record holds them; the process prints nothing."""
    clip = FIXTURES / "bvh/cmu_01_01.bvh"
    r = inbetween.process_file(clip, tmp_path / "a.json", "reduce", tolerance=0.5,
                               translation_tolerance=0.1, verbose=True)
    assert r["status"] == "ok", r
    assert len(r["reports"]) == r["tracks"], r["reports"][:3]
    assert all(line.startswith("inbetween: reduce: track ") for line in r["reports"])
    out, err = capfd.readouterr()
    assert out == "" and err == ""
