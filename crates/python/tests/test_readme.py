"""The README's Python example and docs/python.md's notebook run (its plot only where matplotlib
is installed)."""

from __future__ import annotations

import importlib.util
import os
import re

import pytest

from conftest import REPO


def python_blocks(page: str, heading: str) -> list[str]:
    text = (REPO / page).read_text()
    section = text.split(f"\n## {heading}\n", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"```python\n(.*?)```", section, flags=re.S)


def test_readme_example_runs(monkeypatch, capsys):
    (block,) = python_blocks("README.md", "In Python")
    monkeypatch.chdir(REPO)
    exec(compile(block, "README.md (Python example)", "exec"), {})
    before, after = capsys.readouterr().out.split("->")
    assert int(after) < int(before)


def test_notebook_runs(monkeypatch, capsys):
    pytest.importorskip("csaps")
    blocks = python_blocks("docs/python.md", "A notebook's worth")
    assert len(blocks) == 2 and "csaps" in blocks[0] and "matplotlib" in blocks[1]
    monkeypatch.chdir(REPO)
    namespace: dict = {}
    exec(compile(blocks[0], "docs/python.md (notebook)", "exec"), namespace)
    printed = capsys.readouterr().out
    assert "jump-lsq: inflections" in printed and "csaps at the same M_d" in printed
    if importlib.util.find_spec("matplotlib") is None:
        return  # the plot is optional
    monkeypatch.setenv("MPLBACKEND", "Agg")
    exec(compile(blocks[1], "docs/python.md (plot)", "exec"), namespace)
    import matplotlib.pyplot as plt

    lines = plt.gca().get_lines()
    assert [line.get_label() for line in lines] == ["measured", "csaps, same M_d", "fair jump-lsq"]
    plt.close("all")
