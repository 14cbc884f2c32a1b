"""Building a message through the typed view of its type: the type checker (mypy, with the
package's own configuration) reports a misspelt field and a value of the wrong type, in
`new` and in `make`, and accepts a message built right."""

from __future__ import annotations

import re
import subprocess
import sys
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
MYPY_DEADLINE_S = 120

SNIPPET = textwrap.dedent(
    """\
    from egosim.msgs import get_profile

    profile = get_profile("26.r1")
    ctrl = profile.message("morai_msgs/CtrlCmd")
    ctrl.new(longlCmdType=1, accel=0.5)
    ctrl.new(longlCmdType=1, acel=0.5)
    ctrl.new(longlCmdType="one")
    ctrl.make(longlCmdType=1, accel=0.5, brake=0.0, front_steer=0.0, rear_steer=0.0,
              velocity=0.0, acceleration=0.0, steering=0.0)
    ctrl.make(longlCmdType=1, accel="0.5", brake=0.0, front_steer=0.0, rear_steer=0.0,
              velocity=0.0, acceleration=0.0)
    """
)
# snippet line -> what mypy must say of it
EXPECTED = {
    6: 'Unexpected keyword argument "acel"',
    7: 'Argument "longlCmdType" to "new" of "CtrlCmdType" has incompatible type "str"; '
    'expected "int"',
    8: 'Unexpected keyword argument "steering"',
    10: 'Argument "accel" to "CtrlCmd" has incompatible type "str"; expected "float"',
}


def test_mypy_reports_a_wrong_field_name_and_a_wrong_field_type(tmp_path: Path) -> None:
    snippet = tmp_path / "snippet.py"
    snippet.write_text(SNIPPET, encoding="utf-8")
    checked = subprocess.run(
        [
            sys.executable,
            "-m",
            "mypy",
            "--config-file",
            str(ROOT / "pyproject.toml"),
            "--cache-dir",
            str(tmp_path / "mypy_cache"),
            "--no-error-summary",
            str(snippet),
        ],
        capture_output=True,
        text=True,
        timeout=MYPY_DEADLINE_S,
        cwd=tmp_path,
        check=False,
    )
    errors: dict[int, list[str]] = {}
    for match in re.finditer(r"^.*snippet\.py:(\d+): error: (.*)$", checked.stdout, re.M):
        errors.setdefault(int(match.group(1)), []).append(match.group(2))
    assert set(errors) == set(EXPECTED), checked.stdout + checked.stderr
    for line, message in EXPECTED.items():
        assert any(message in error for error in errors[line]), (line, errors[line])
