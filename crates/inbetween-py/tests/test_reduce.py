"""`inbetween.reduce`: the guarantee as a user checks it, and the command line's keys."""

import json
import subprocess

import numpy as np
import pytest

import inbetween
from conftest import angle, frames_csv
from test_resample import motion


@pytest.mark.parametrize("scheme", ["hermite", "squad", "bezier", "slerp", "nlerp", "minaccel"])
def test_the_keys_curve_gives_every_frame_back(scheme):
    q = motion(361, 3, 120)
    r = inbetween.reduce(q, 120, 0.5, scheme=scheme)
    assert len(r) == 3 and r.joints == 3
    t = inbetween.frame_times(361, 120, 120)
    for j in range(3):
        keys = r.keys[j]
        assert keys[0] == 0 and keys[-1] == 360 and len(keys) < 361 / 4, (scheme, len(keys))
        err = np.degrees(angle(r.curve(q, j)(t), q[:, j]))
        assert err.max() <= 0.5, (scheme, j, err.max())
        assert abs(err.max() - r.max_error[j]) < 1e-9


def test_one_joint_radians_shared_keys_and_translations():
    q = motion(241, 4, 60)
    one = inbetween.reduce(q[:, 1], 60, 0.25)
    assert one.joints is None and len(one) == 1
    assert np.array_equal(one.keys[0], inbetween.reduce(q, 60, 0.25).keys[1])
    rad = inbetween.reduce(q, 60, np.radians(0.25), degrees=False)
    assert all(np.array_equal(a, b) for a, b in zip(rad.keys, inbetween.reduce(q, 60, 0.25).keys))
    assert np.allclose(np.degrees(rad.max_error), inbetween.reduce(q, 60, 0.25).max_error)
    shared = inbetween.reduce(q, 60, 0.25, shared_keys=True)
    assert all(np.array_equal(k, shared.keys[0]) for k in shared.keys)
    p = np.cumsum(np.ones((241, 4, 3)) * 0.01, axis=0) ** 2
    moved = inbetween.reduce(q, 60, 0.25, translations=p, translation_tolerance=1e-3)
    assert (moved.max_position_error <= 1e-3).all()
    plain = inbetween.reduce(q, 60, 0.25, velocities=False)
    assert plain.velocities[0] is None


def test_agrees_with_the_command_line(cli, tmp_path):
    q = motion(361, 3, 120)
    src = frames_csv(tmp_path / "frames.csv", q)
    for extra, kwargs in [([], {}), (["--method", "optimal", "--scheme", "squad"],
                                     {"method": "optimal", "scheme": "squad"})]:
        out = tmp_path / "keys.json"
        subprocess.run([cli, "reduce", str(src), "--key-fps", "120", "--tolerance", "0.5",
                        *extra, "-o", str(out)], check=True)
        doc = json.loads(out.read_text())
        r = inbetween.reduce(q, 120, 0.5, **kwargs)
        for j, track in enumerate(doc["tracks"]):
            frames = [k["frame"] for k in track["keys"]]
            assert frames == r.keys[j].tolist(), (extra, j)
            for key, v in zip(track["keys"], r.velocities[j]):
                # The CLI writes velocities in --angles units (degrees per second).
                assert np.allclose(np.radians(key["velocity"]), v, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize(
    "kwargs, says",
    [
        ({"tolerance": 1e-12, "degrees": False}, "tolerance: 1e-12 is below what reduce can verify"),
        ({"tolerance": 0.5, "method": "best"}, "method: expected greedy or optimal"),
        ({"tolerance": 0.5, "translations": np.zeros((50, 3))}, "translation_tolerance: the frames have translations"),
        ({"tolerance": 0.5, "translations": np.zeros((49, 3)), "translation_tolerance": 1.0}, "translations: shape"),
    ],
)
def test_errors_name_the_argument(kwargs, says):
    q = motion(50, 1, 30)[:, 0]
    with pytest.raises(inbetween.InputError) as e:
        inbetween.reduce(q, 30, **kwargs)
    assert says in str(e.value)
