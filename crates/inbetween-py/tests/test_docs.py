"""docs/python.md's examples run as written: every ```python block, in order, in one namespace,
from the repository's root."""

import re

from conftest import ROOT


def test_python_md_examples_run(monkeypatch):
    monkeypatch.chdir(ROOT)  # the examples name files from the repository's root
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
