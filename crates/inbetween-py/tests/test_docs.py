"""docs/python.md's examples run as written: every ```python block, in order, in one namespace,
in a folder with the repository's fixtures."""

import re

from conftest import ROOT
from inbetween import read as inbetween_read


def test_python_md_examples_run(monkeypatch, tmp_path):
    # The examples read files from the repository's root and write beside them: run them in a
    # folder that has the fixtures.
    (tmp_path / "fixtures").symlink_to(ROOT / "fixtures")
    monkeypatch.chdir(tmp_path)
    text = (ROOT / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert len(blocks) >= 2
    namespace = {}
    for block in blocks:
        exec(compile(block, "docs/python.md", "exec"), namespace)
    assert namespace["q"].shape == (61, 4) and namespace["w"].shape == (61, 3)
    assert namespace["frames"].shape[1:] == (60, 4)
    assert namespace["err"].max() <= 0.5
    assert namespace["clip"].rotations.shape == (61, 31, 4)
    assert (tmp_path / "wheel.csv").read_text().splitlines()[2].endswith(",30.000,0.000,0.000")
    assert inbetween_read(tmp_path / "cmu_copy.bvh").rotations.shape == (61, 31, 4)
    small = inbetween_read(tmp_path / "cesium_small.glb")
    assert small.names == namespace["man"].names and small.times is None  # keys per track
    assert inbetween_read(tmp_path / "cesium_copy.gltf").rotations.shape == (48, 19, 4)
