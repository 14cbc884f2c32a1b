"""The wire contract of morai_msgs, shipped beside the project in shared/protocol/."""

from __future__ import annotations

import json
import os
from functools import cache
from pathlib import Path
from typing import Any

import pytest


def protocol_dir() -> Path:
    """`shared/protocol` next to the checkout (or $EGOSIM_PROTOCOL_DIR)."""
    if env := os.environ.get("EGOSIM_PROTOCOL_DIR"):
        return Path(env)
    repo = Path(__file__).resolve().parents[1]
    for candidate in (repo.parent / "shared" / "protocol", repo / "shared" / "protocol"):
        if candidate.is_dir():
            return candidate
    pytest.skip("shared/protocol (the morai_msgs contract) is not beside the checkout")


@cache
def load_contract(profile: str = "26.r1") -> dict[str, Any]:
    return json.loads((protocol_dir() / f"morai_msgs-{profile}.json").read_text())
