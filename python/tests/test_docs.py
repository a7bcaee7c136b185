"""Every Python block of the guide's Python page and of the README runs (in an empty
directory); a Python block followed by a text block prints that text; the page's
`python -m hibi.dataset` commands run."""

import pathlib
import re
import shlex
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAGES = [ROOT / "docs" / "src" / "python.md", ROOT / "README.md"]
FENCE = re.compile(r"^```(\w*)\n(.*?)^```\n", re.S | re.M)


def blocks():
    out = []
    for page in PAGES:
        found = list(FENCE.finditer(page.read_text()))
        for n, m in enumerate(found):
            if m.group(1) != "python":
                continue
            after = found[n + 1] if n + 1 < len(found) else None
            gap = page.read_text()[m.end() : after.start()] if after else "x"
            expected = after.group(2) if after and after.group(1) == "text" and not gap.strip() else None
            line = page.read_text()[: m.start()].count("\n") + 1
            out.append(pytest.param(m.group(2), expected, id=f"{page.name}:{line}"))
    return out


def test_the_pages_have_python_blocks():
    assert len(blocks()) >= 8


@pytest.mark.parametrize("code, expected", blocks())
def test_python_block_runs(code, expected, tmp_path):
    run = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    if expected is not None:
        assert run.stdout == expected


def test_the_dataset_commands_run(tmp_path):
    page = (ROOT / "docs" / "src" / "python.md").read_text()
    commands = [line for line in page.splitlines() if line.startswith("python -m hibi.dataset ")]
    assert len(commands) >= 2
    for command in commands:
        argv = [sys.executable] + shlex.split(command)[1:] + ["--quiet"]
        run = subprocess.run(argv, cwd=tmp_path, capture_output=True, text=True, timeout=600)
        assert run.returncode == 0, (command, run.stderr)
    assert len(list(tmp_path.glob("*/shard-*/annotations.json"))) >= 3
