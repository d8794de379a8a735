"""`inbetween.write` to .glb and .gltf: the clip's keys written into the asset it was read from,
read back by `inbetween.read` and played by the independent reference
(fixtures/gltf/playback_ref.py), valid for the Khronos glTF Validator, and the bytes `inbetween
reduce X.glb --scheme slerp -o Y.glb` writes for the same keys."""

import json
import pathlib
import shutil
import struct
import subprocess

import numpy as np
import pytest

import inbetween
from conftest import FIXTURES, angle

GLTF = FIXTURES / "gltf"
# float32 storage: about 2.4e-7 rad per rotation, as the command line's margin (1e-6 rad).
F32_RAD = 1e-6


def gltf_json(path):
    data = pathlib.Path(path).read_bytes()
    if data[:4] == b"glTF":
        (length,) = struct.unpack_from("<I", data, 12)
        return json.loads(data[20:20 + length])
    return json.loads(data)


def channels(path):
    """Per track name (as `read` names them: the node, or `animation/node` for several
    animations), `(animation, rotation channel, translation channel or None)` indices."""
    g = gltf_json(path)
    anims = [(i, a) for i, a in enumerate(g["animations"])
             if any(c["target"].get("path") == "rotation" for c in a["channels"])]
    out = {}
    for i, a in anims:
        label = a.get("name", str(i))
        for c, ch in enumerate(a["channels"]):
            if ch["target"].get("path") != "rotation":
                continue
            node = ch["target"]["node"]
            name = g["nodes"][node].get("name", f"node{node}")
            tr = next((k for k, t in enumerate(a["channels"])
                       if t["target"].get("path") == "translation" and t["target"]["node"] == node),
                      None)
            out[f"{label}/{name}" if len(anims) > 1 else name] = (i, c, tr)
    return out


def wxyz(rows):
    return np.array(rows)[:, [3, 0, 1, 2]]


def same_tracks(clip, back, translations_atol=0.0):
    assert back.names == clip.names
    for (t0, q0, p0), (t1, q1, p1) in zip(clip.tracks, back.tracks):
        assert np.array_equal(t0, t1)
        assert np.max(angle(q0, q1)) <= F32_RAD
        assert (p0 is None) == (p1 is None)
        if p0 is not None:
            assert np.max(np.abs(p0 - p1)) <= translations_atol * max(1.0, np.max(np.abs(p0)))


@pytest.mark.parametrize("ext", ["glb", "gltf"])
@pytest.mark.parametrize("name", ["real/CesiumMan.glb", "samplers.glb", "samplers.gltf"])
def test_a_clip_written_into_its_asset_plays_its_keys(tmp_path, gltf_validator, playback, name,
                                                      ext):
    src = GLTF / name
    clip = inbetween.read(src)
    out = tmp_path / f"out.{ext}"
    inbetween.write(out, clip)
    # Read back as any input: the same tracks (samplers' CUBICSPLINE translation, a channel
    # left as read, is sampled with its key times snapped for a LINEAR rotation track and
    # stored for a baked one: 5.5e-7 apart).
    same_tracks(clip, inbetween.read(out), translations_atol=1e-6)
    gltf_validator(out)
    written = channels(out)
    assert written.keys() == channels(src).keys()
    # Every track read back above; a third of CesiumMan's 19 (a process each) played here.
    for n, (t, q, p) in list(zip(clip.names, clip.tracks))[::3]:
        a, c, tr = written[n]
        played = playback(out, a, c, t)
        assert played["interpolation"] == "LINEAR"
        assert np.max(angle(wxyz(played["rotations"]), q)) <= F32_RAD, n
        if p is not None and n == clip.names[0]:
            # Translations as read leave the node's channel as it was.
            was = playback(src, *channels(src)[n][::2], t)
            now = playback(out, a, tr, t)
            assert now["interpolation"] == was["interpolation"]
            assert now["values"] == was["values"]


@pytest.mark.parametrize("ext", ["glb", "gltf"])
def test_keys_reduced_for_slerp_are_what_reduce_writes(cli, tmp_path, playback, ext):
    src = GLTF / "real" / "CesiumMan.glb"
    clip = inbetween.read(src)  # 48 frames at 24 fps, every joint on them
    # reduce to glTF tightens the tolerance by 1e-6 rad for float32 storage.
    r = inbetween.reduce(clip.rotations, 24, np.degrees(np.radians(0.5) - 1e-6), scheme="slerp")
    small = clip.with_tracks({n: (clip.times[k], clip.rotations[k, j], None)
                              for j, (n, k) in enumerate(zip(clip.names, r.keys))})
    ours, theirs = tmp_path / f"ours.{ext}", tmp_path / f"theirs.{ext}"
    inbetween.write(ours, small)
    # Without a translation tolerance reduce leaves the translation channels as read, as
    # tracks without translations do.
    subprocess.run([cli, "reduce", str(src), "--scheme", "slerp", "--tolerance", "0.5", "-o",
                    str(theirs)], check=True)
    assert ours.read_bytes() == theirs.read_bytes()
    back = inbetween.read(ours)
    assert [len(t) for t, _, _ in back.tracks] == [len(k) for k in r.keys]
    assert sum(len(k) for k in r.keys) < 0.5 * clip.rotations.shape[0] * len(clip)
    # Played by slerp (a glTF LINEAR sampler), every frame is within the tolerance.
    for n in clip.names[:3]:
        a, c, _ = channels(ours)[n]
        played = wxyz(playback(ours, a, c, clip.times)["rotations"])
        assert np.degrees(np.max(angle(played, clip.track(n)[1]))) <= 0.5


def test_translations_are_written_into_the_nodes_channel(tmp_path, gltf_validator, playback):
    src = GLTF / "real" / "CesiumMan.glb"
    clip = inbetween.read(src)
    name = clip.names[0]
    t, q, p = clip.track(name)
    moved = p + np.array([0.0, 0.25, -0.5])
    out = tmp_path / "moved.glb"
    inbetween.write(out, clip.with_tracks({**dict(zip(clip.names, clip.tracks)),
                                           name: (t, q, moved)}))
    gltf_validator(out)
    back = inbetween.read(out)
    assert np.array_equal(back.track(name)[2], moved.astype(np.float32).astype(np.float64))
    for n in clip.names[1:]:
        assert np.array_equal(back.track(n)[2], clip.track(n)[2])  # channels as read
    a, _, tr = channels(out)[name]
    played = playback(out, a, tr, t)
    assert played["interpolation"] == "LINEAR" and played["path"] == "translation"
    assert np.max(np.abs(np.array(played["values"]) - moved)) <= 1e-6


def cesium(tmp_path):
    return inbetween.read(GLTF / "real" / "CesiumMan.glb")


def samplers(tmp_path):
    return inbetween.read(GLTF / "samplers.glb")


@pytest.mark.parametrize(
    "call, says",
    [
        (lambda d: inbetween.write(d / "x.glb", inbetween.read(FIXTURES / "bvh" / "cmu_01_01.bvh")),
         "path: {d}/x.glb: glTF output is written into the glTF asset the clip was read from"),
        (lambda d: inbetween.write(d / "x.gltf", inbetween.Clip.from_arrays([0.0], [[1, 0, 0, 0]])),
         "this clip was made from arrays"),
        (lambda d: inbetween.write(d / "x.glb", cesium(d).with_tracks({"Nope": cesium(d).tracks[0]})),
         'tracks[0] ("Nope"): '),
        (lambda d: inbetween.write(d / "x.glb", samplers(d).with_tracks(
            {"Mixed/step": (*samplers(d).tracks[0][:2], np.zeros((8, 3)))})),
         'tracks[0] ("Mixed/step") translations: '),
        (lambda d: inbetween.write(d / "x.glb", cesium(d).with_tracks(
            {"torso_joint_3": ([1.0, 1.0 + 1e-9], [[1, 0, 0, 0]] * 2, None)})),
         'tracks[0] ("torso_joint_3") times[1]: 1 s and 1.000000001 s are the same float32'),
        (lambda d: inbetween.write(d / "x.glb", cesium(d).with_tracks(
            {"torso_joint_3": ([-1.0, 1.0], [[1, 0, 0, 0]] * 2, None)})),
         "times[0]: expected a finite time of at least 0 s"),
        (lambda d: inbetween.write(d / "x.glb", cesium(d), to="euler:ZYX"), "to: glTF stores"),
        (lambda d: inbetween.write(d / "x.gltf", cesium(d), precision=3), "precision: glTF"),
    ],
)
def test_errors_write_nothing(tmp_path, call, says):
    with pytest.raises(inbetween.InputError) as e:
        call(tmp_path)
    message = str(e.value)
    assert says.format(d=tmp_path) in message, message
    assert "--" not in message and " -o " not in message, "no command-line flag"
    assert list(tmp_path.iterdir()) == []


def test_unknown_track_lists_the_assets_tracks(tmp_path):
    clip = cesium(tmp_path)
    with pytest.raises(inbetween.InputError) as e:
        inbetween.write(tmp_path / "x.glb", clip.with_tracks({"Nope": clip.tracks[0]}))
    assert 'no rotation channel for track "Nope"' in str(e.value)
    assert '"Skeleton_torso_joint_1"' in str(e.value)


def test_the_source_asset_must_be_there_as_read(tmp_path):
    src = tmp_path / "a.glb"
    shutil.copy(GLTF / "real" / "CesiumMan.glb", src)
    clip = inbetween.read(src)
    inbetween.write(src, clip)  # written over its own asset: read before it is replaced
    assert inbetween.read(src).names == clip.names
    with pytest.raises(inbetween.InputError) as e:
        inbetween.write(tmp_path / "b.glb", clip)  # the asset is now another one
    assert "the asset changed since the clip was read from it" in str(e.value)
    src.unlink()
    with pytest.raises(inbetween.InputError) as e:
        inbetween.write(tmp_path / "b.glb", clip)
    assert f"{src}: the clip's source asset cannot be read" in str(e.value)
    assert list(tmp_path.iterdir()) == []
