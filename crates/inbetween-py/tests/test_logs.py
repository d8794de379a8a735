"""Timestamped logs (issue 47): `read(path, columns=...)` of the TUM, EuRoC and `rostopic echo
-p` files of fixtures/logs gives the keys of their plain CSV twins, which this test parses with
Python's own csv module (both files written by fixtures/logs/generate.py, not by inbetween)."""

import csv
import subprocess

import numpy as np
import pytest

import inbetween
from conftest import FIXTURES, angle

LOGS = FIXTURES / "logs"


def twin(path):
    """The plain CSV twin: times (K,), unit quaternions (K, 4) w first, translations or None."""
    with open(f"{path}.expected.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    times = np.array([float(r["time"]) for r in rows])
    q = np.array([[float(r[c]) for c in "wxyz"] for r in rows])
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    p = (np.array([[float(r[c]) for c in ("tx", "ty", "tz")] for r in rows])
         if "tx" in rows[0] else None)
    return times, q, p


@pytest.mark.parametrize("name,preset", [
    ("tum_groundtruth.txt", "tum"),
    ("euroc_groundtruth.csv", "euroc"),
    ("euroc_vicon.csv", "euroc"),
    ("rostopic_pose.csv", "rostopic"),
    ("rostopic_imu.csv", "rostopic"),
])
def test_presets_read_the_keys_of_the_twin(name, preset):
    clip = inbetween.read(LOGS / name, columns=preset)
    assert len(clip) == 1
    times, q, p = clip.tracks[0]
    want_t, want_q, want_p = twin(LOGS / name)
    # Times from integer stamps, exact: the same doubles as the decimals of the twin.
    assert np.array_equal(times, want_t), name
    assert np.max(angle(q, want_q)) < 1e-12, name
    assert np.max(np.abs(q - want_q)) < 1e-15, name
    if want_p is None:
        assert p is None
    else:
        assert np.array_equal(p, want_p), name


def test_nanosecond_stamps_1_ns_apart_stay_apart():
    clip = inbetween.read(LOGS / "euroc_groundtruth.csv", columns="euroc")
    times = clip.tracks[0][0]
    assert times[5] - times[4] == pytest.approx(1e-9, rel=1e-6)
    assert float(1403636579758555392) == float(1403636579758555393)  # why it matters


def test_column_maps_as_text_and_as_dicts():
    pose = LOGS / "rostopic_pose.csv"
    stamp_t, _, _ = twin(LOGS / "rostopic_pose.stamp")
    by_text = inbetween.read(pose, columns="rostopic,time=field.header.stamp")
    by_dict = inbetween.read(pose, columns={"preset": "rostopic", "time": "field.header.stamp"})
    assert np.array_equal(by_text.tracks[0][0], stamp_t)
    assert np.array_equal(by_dict.tracks[0][0], stamp_t)
    tum = LOGS / "tum_groundtruth.txt"
    numbers = inbetween.read(tum, columns={"time": 1, "tx": 2, "ty": 3, "tz": 4, "x": 5, "y": 6,
                                           "z": 7, "w": 8})
    preset = inbetween.read(tum, columns="tum")
    for a, b in zip(numbers.tracks[0], preset.tracks[0]):
        assert np.array_equal(a, b)


def test_time_unit_and_absolute_times(tmp_path):
    log = tmp_path / "us.csv"
    log.write_text("stamp,qw,qx,qy,qz\n1403636579758555,1,0,0,0\n1403636579758556,0,0,0,1\n")
    cols = {"time": "stamp", "w": "qw", "x": "qx", "y": "qy", "z": "qz"}
    assert list(inbetween.read(log, columns=cols, time_unit="us").tracks[0][0]) == [0.0, 1e-6]
    absolute = inbetween.read(LOGS / "tum_groundtruth.txt", columns="tum", times="absolute")
    assert absolute.tracks[0][0][0] == 1305031098.6659


@pytest.mark.parametrize("kwargs,message", [
    (dict(columns="rostopic,time=field.header.stmp"),
     'rostopic_pose.csv:1: no column "field.header.stmp" for field time'),
    (dict(columns="rostopic", time_unit="bogus"), "time_unit: expected a time unit s, ms, us or ns"),
    (dict(time_unit="ns"), "time_unit and times describe the stamps of a log read with columns"),
    (dict(columns={"time": 0}), 'columns["time"]: expected a column number from 1'),
    (dict(columns={"tim": 1}), 'columns: unknown field "tim"'),
    (dict(columns="ros"), "columns: expected a preset (tum, euroc, rostopic)"),
])
def test_bad_maps_are_input_errors(kwargs, message):
    with pytest.raises(inbetween.InputError) as e:
        inbetween.read(LOGS / "rostopic_pose.csv", **kwargs)
    assert message in str(e.value)


def test_bad_stamps_are_located(tmp_path):
    log = tmp_path / "b.csv"
    log.write_text("%time,field.x,field.y,field.z,field.w\n20,0,0,0,1\n10,0,0,0,1\n")
    with pytest.raises(inbetween.InputError, match=r"b\.csv:3: column \"%time\" \(time\): "
                                                   r"expected stamps that increase"):
        inbetween.read(log, columns="rostopic")


def test_process_file_takes_columns_as_the_command_line(tmp_path, cli):
    tum = LOGS / "tum_groundtruth.txt"
    out = tmp_path / "frames.csv"
    record = inbetween.process_file(tum, out, "interp", columns="tum", fps=200,
                                    times="relative")
    assert record["status"] == "ok"
    want = subprocess.run([cli, "interp", str(tum), "--columns", "tum", "--fps", "200"],
                          check=True, capture_output=True).stdout
    assert out.read_bytes() == want
