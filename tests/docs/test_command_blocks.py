"""The README and docs/*.md say what works: each of their command blocks runs as written.

Blocks run in the order of their file, in bash (or egosim's Python for `python` blocks)
from the checkout, as a user pastes them into a terminal: one HOME for the whole file (so
`~/morai_py` exported by one block serves the next), ROS's command-line tools and Debian's
/usr/bin/python3 at hand. "The checkout" is a directory of links to the checkout's
entries, so what the blocks write there (a bag recorded in the clone) stays out of it and
cannot clash with a file of the same name. The one edit made to a block's text is the
master's address: the README's default http://localhost:11311 becomes a free loopback
port. A block marked `simulator` (`make run`, `egosim run ...`) is started in the
background and waited for; the blocks after it run against it. A `prints` block holds
lines the command block before it must print. See tests/docs/blocks.py for the markers.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

from tests.conftest import RosProcess, free_port
from tests.debian_ros import require_ros
from tests.docs.blocks import PYTHON_LANGUAGES, Block, parse_blocks

REPO = Path(__file__).parents[2]
DOCUMENTS = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]
DEFAULT_MASTER = "http://localhost:11311"
READY = "egosim: ready"
BLOCK_TIMEOUT_S = 120.0
READY_TIMEOUT_S = 120.0


def runnable(document: Path) -> list[Block]:
    return [b for b in parse_blocks(document) if b.action in ("run", "simulator")]


@pytest.mark.parametrize("document", DOCUMENTS, ids=lambda p: p.name)
def test_markers_are_well_formed(document: Path) -> None:
    blocks = parse_blocks(document)  # MarkerError on a bad or stray marker
    for index, block in enumerate(blocks):
        before = blocks[index - 1] if index else None
        if block.action == "simulator":
            assert block.language in ("sh", "bash", "shell"), block.where
        if block.action == "skip":
            assert len(block.reason) > 10, f"{block.where}: say why it cannot run"
        if block.action == "prints":
            assert block.language == "", f"{block.where}: output is an untagged block"
            assert before is not None and before.action == "run", (
                f"{block.where}: what it prints follows the command block that prints it"
            )


def checkout_view(directory: Path) -> Path:
    """`directory` holding a link to each entry of the checkout: where the blocks run."""
    directory.mkdir()
    for entry in REPO.iterdir():
        (directory / entry.name).symlink_to(entry)
    return directory


def run_block(block: Block, text: str, env: dict[str, str], cwd: Path) -> str:
    """Run one block to its end in `cwd`; its output. Fails with the output unless it
    exits 0."""
    if block.language in PYTHON_LANGUAGES:
        command = [sys.executable, "-c", text]
    else:
        command = ["bash", "-e", "-o", "pipefail", "-c", text]
    process = subprocess.Popen(
        command,
        cwd=cwd,
        env=env,
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,
    )
    try:
        output, _ = process.communicate(timeout=BLOCK_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        output = ""
    finally:
        # Whatever the block left in the background (`rostopic pub ... &`) goes with it.
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, signal.SIGKILL)
        process.wait()
    assert process.returncode == 0, (
        f"{block.where}: exit status {process.returncode}\n{text}\n--- output:\n{output[-4000:]}"
    )
    return output


def check_output(block: Block, output: str) -> None:
    """A `prints` block: each of its lines is a line the block before it printed."""
    printed = {line.strip() for line in output.splitlines()}
    for expected in block.text.splitlines():
        assert expected.strip() in printed, (
            f"{block.where}: {expected.strip()!r} was not printed; the output:\n{output[-4000:]}"
        )


def check_printed(block: Block, simulator: RosProcess) -> None:
    """An output block after a simulator block shows what the simulator prints: it must."""
    for expected in block.text.splitlines()[1:]:
        line = simulator.expect(r".").string
        assert line == expected, f"{block.where}: the simulator printed {line!r}"


@pytest.mark.ros
@pytest.mark.parametrize("document", [d for d in DOCUMENTS if runnable(d)], ids=lambda p: p.name)
def test_command_blocks_run_as_written(
    document: Path,
    spawn_ros: Callable[..., RosProcess],
    ros_env: dict[str, str],
    tmp_path: Path,
) -> None:
    require_ros()
    if not (REPO / ".venv" / "bin" / "egosim").exists():
        pytest.skip("the documents' commands use the checkout's .venv, which `make run` creates")
    home = tmp_path / "home"
    home.mkdir()
    master_uri = f"http://127.0.0.1:{free_port()}"
    env = dict(ros_env, HOME=str(home), ROS_MASTER_URI=master_uri, ROS_IP="127.0.0.1")
    checkout = checkout_view(tmp_path / "checkout")
    simulator: RosProcess | None = None
    just_started = False
    output = ""
    for block in parse_blocks(document):
        text = block.text.replace(DEFAULT_MASTER, master_uri)
        if just_started and block.language == "" and block.text.startswith(READY + "\n"):
            assert simulator is not None
            check_printed(block, simulator)
        just_started = False
        if block.action == "simulator":
            if simulator is not None:
                simulator.kill()
            simulator = spawn_ros(
                ["bash", "-e", "-c", f"cd {checkout}\n{text}"],
                master_uri=master_uri,
                HOME=str(home),
                ROS_IP="127.0.0.1",
            )
            simulator.expect(f"^{READY}$", timeout=READY_TIMEOUT_S)
            just_started = True
        elif block.action == "run":
            output = run_block(block, text, env, checkout)
        elif block.action == "prints":
            check_output(block, output)
