"""Runs docs/tutorial.md as a reader would: its `sh` and `python` blocks in
order in one shell, after writing the files of its `simit`/`json` blocks
marked `file=NAME`; a `text` block must appear in the output of the block
before it. HOME is a fresh folder, so `~/simit` and `~/rope` are made anew;
the install uses the build under test ($SIMIT_BUILD_DIR, default build/)."""

import os
import re
import subprocess
import sys

from conftest import ROOT

TUTORIAL = ROOT / "docs" / "tutorial.md"
FENCE = re.compile(r"^```(\w+)([^\n]*)\n(.*?)^```$", re.M | re.S)


def blocks(markdown):
    """(language, file name or None, text) of each fenced block."""
    for match in FENCE.finditer(markdown):
        file = re.search(r"file=(\S+)", match.group(2))
        yield match.group(1), file.group(1) if file else None, match.group(3)


def script(markdown, logs):
    """One bash script running the blocks, block i's output in logs/i."""
    lines = ["set -eo pipefail", f"cd {ROOT}"]
    expected = {}
    last_run = None
    for i, (language, file, text) in enumerate(blocks(markdown)):
        if file:
            lines += [f"cat > {file} <<'SIMIT_TUTORIAL_FILE'", text.rstrip("\n"),
                      "SIMIT_TUTORIAL_FILE"]
        elif language == "sh":
            lines += ["{", text, f"}} > {logs}/{i} 2>&1"]
            last_run = i
        elif language == "python":
            lines += [f"python3 - > {logs}/{i} 2>&1 <<'SIMIT_TUTORIAL_PY'",
                      text.rstrip("\n"), "SIMIT_TUTORIAL_PY"]
            last_run = i
        elif language == "text":
            assert last_run is not None, "a text block before any command"
            expected[last_run] = text
    return "\n".join(lines) + "\n", expected


def test_every_command_of_the_tutorial_runs(tmp_path):
    logs = tmp_path / "logs"
    home = tmp_path / "home"
    logs.mkdir()
    home.mkdir()
    text, expected = script(TUTORIAL.read_text(), logs)
    env = dict(os.environ, HOME=str(home))
    # The tutorial's python3 is this one (Debian's), with its packages.
    env["PATH"] = os.path.dirname(sys.executable) + os.pathsep + env["PATH"]
    env.pop("PYTHONPATH", None)  # the tutorial sets it to the install
    run = subprocess.run(["bash", "-c", text], env=env, capture_output=True,
                         text=True)
    outputs = {int(name): (logs / name).read_text()
               for name in os.listdir(logs)}
    failed = max(outputs) if outputs else None
    assert run.returncode == 0, (
        f"the tutorial stopped at block {failed}:\n{outputs.get(failed, '')}"
        f"\n{run.stderr}")
    for block, text in expected.items():
        for line in text.strip().splitlines():
            assert line in outputs[block], (
                f"block {block} did not print {line!r}:\n{outputs[block]}")
