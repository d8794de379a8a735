"""`inbetween.read`: every input format, the same tracks the command line reads."""

import json
import subprocess

import numpy as np
import pytest

import inbetween
from conftest import FIXTURES, angle


def convert_json(cli, path, tmp_path):
    out = tmp_path / "keys.json"
    subprocess.run([cli, "convert", str(path), "-o", str(out)], check=True)
    return json.loads(out.read_text())


@pytest.mark.parametrize("name", ["bvh/cmu_01_01.bvh", "bvh/cmu_01_01_positions.bvh",
                                  "gltf/real/RiggedSimple.gltf", "gltf/real/CesiumMan.glb",
                                  "interp/multitrack.json", "convert/two_tracks.csv"])
def test_the_tracks_convert_writes(cli, tmp_path, name):
    path = FIXTURES / name
    clip = inbetween.read(path)
    doc = convert_json(cli, path, tmp_path)
    assert len(clip) == len(doc["tracks"])
    fps = float(eval(clip.fps)) if clip.fps else 30.0
    for (times, q, p), track in zip(clip.tracks, doc["tracks"]):
        keys = track["keys"]
        want_t = np.array([k["time"] if "time" in k else k["frame"] / fps for k in keys])
        assert np.allclose(times, want_t, rtol=0, atol=1e-12), name
        want_q = np.array([k["quat"] for k in keys])
        assert np.max(angle(q, want_q)) < 1e-12, name
        if "translation" in keys[0]:
            assert np.array_equal(p, np.array([k["translation"] for k in keys])), name
        else:
            assert p is None
        if "name" in track:
            assert track["name"] in clip.names


def test_a_bvh_clip_is_arrays_with_its_skeleton():
    clip = inbetween.read(FIXTURES / "bvh" / "cmu_01_01.bvh")
    assert clip.format == "bvh" and clip.fps == "120"
    assert clip.rotations.shape == (61, 31, 4) and clip.times.shape == (61,)
    assert np.allclose(clip.times, np.arange(61) / 120, atol=1e-15)
    assert clip.translations.shape == (61, 31, 3)
    assert clip.has_translation.sum() == 1 and clip.has_translation[0]
    assert clip.parents[0] == -1 and (clip.parents[1:] >= 0).all()
    assert (clip.parents[1:] < np.arange(1, 31)).all()
    assert clip.offsets.shape == (31, 3)
    hips = clip.track("Hips")
    assert np.array_equal(hips[1], clip.rotations[:, 0])
    # A Curve through the clip is a curve through each joint's frames.
    c = inbetween.Curve(clip.times, clip.rotations)
    assert np.max(angle(c(clip.times), clip.rotations)) < 1e-12


def test_tracks_on_their_own_times_are_not_stacked():
    clip = inbetween.read(FIXTURES / "interp" / "multitrack.json")
    assert clip.rotations is None and clip.times is None
    assert all(q.shape == (len(t), 4) for t, q, _ in clip.tracks)


@pytest.mark.parametrize(
    "name, kwargs, says",
    [
        ("nowhere.csv", {}, "nowhere.csv: cannot read"),
        ("bad/nan.csv", {}, "nan.csv"),
        ("interp/spins.csv", {}, "spins.csv"),
        ("interp/spins.csv", {"rotation": "euler:QQQ"}, "rotation:"),
        ("bvh/cmu_01_01.bvh", {"angles": "grad"}, "angles:"),
    ],
)
def test_errors_are_located(tmp_path, name, kwargs, says):
    with pytest.raises(inbetween.InputError) as e:
        inbetween.read(FIXTURES / name, **kwargs)
    assert says in str(e.value)
    assert "--" not in str(e.value)


def test_gltf_parents_and_offsets_are_the_node_hierarchy():
    # Expected from the asset's JSON (the GLB's first chunk), read here: each rotation
    # channel's node, its nearest ancestor animated by another rotation channel, and its rest
    # translation (0 when absent).
    data = (FIXTURES / "gltf/real/CesiumMan.glb").read_bytes()
    length = int.from_bytes(data[12:16], "little")
    doc = json.loads(data[20:20 + length])
    assert len(doc["animations"]) == 1
    nodes = doc["nodes"]
    parent = {c: i for i, n in enumerate(nodes) for c in n.get("children", [])}
    animated = [c["target"]["node"] for c in doc["animations"][0]["channels"]
                if c["target"]["path"] == "rotation"]

    def up(node):
        node = parent.get(node)
        while node is not None and node not in animated:
            node = parent.get(node)
        return -1 if node is None else animated.index(node)

    clip = inbetween.read(FIXTURES / "gltf/real/CesiumMan.glb")
    assert list(clip.parents) == [up(n) for n in animated]
    assert sorted(clip.parents)[:2] == [-1, 0]
    want = np.array([nodes[n].get("translation", [0.0, 0.0, 0.0]) for n in animated])
    np.testing.assert_allclose(clip.offsets, want, rtol=0, atol=1e-7)


def test_a_clip_of_several_gltf_animations_has_no_parents():
    # RiggedSimple animates each of its two nodes in an animation of its own.
    clip = inbetween.read(FIXTURES / "gltf/real/RiggedSimple.gltf")
    assert clip.parents is None and clip.offsets is None
