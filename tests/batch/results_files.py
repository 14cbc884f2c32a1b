"""results.json as tests read and compare it."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any


def read_results(out: Path) -> dict[str, Any]:
    return json.loads((out / "results.json").read_text())


def comparable(document: dict[str, Any]) -> dict[str, Any]:
    """results.json without its wall-clock parts."""
    document = dict(document)
    document.pop("execution")
    document["cases"] = [{k: v for k, v in c.items() if k != "timings"} for c in document["cases"]]
    return document
