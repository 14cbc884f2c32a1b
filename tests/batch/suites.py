"""Suite files written for tests."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import yaml

STRAIGHT_SCENARIO = {"map": "straight", "ego": {"start": {"lane": "R1_E_1", "s": 10.0}}}


def write_suite(
    folder: Path, suite: dict[str, Any], scenario: dict[str, Any] | None = None
) -> Path:
    """`suite` as folder/suite.yaml, next to the scenario it names (scenario.yaml)."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "scenario.yaml").write_text(yaml.safe_dump(scenario or STRAIGHT_SCENARIO))
    path = folder / "suite.yaml"
    path.write_text(yaml.safe_dump(suite, sort_keys=False))
    return path
