"""The wire contract of morai_msgs: each release's md5sums and full definitions, kept in
the repository as test data (tests/data/protocol/)."""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path
from typing import Any

PROTOCOL_DIR = Path(__file__).resolve().parent / "data" / "protocol"


@cache
def load_contract(profile: str = "26.r1") -> dict[str, Any]:
    return json.loads((PROTOCOL_DIR / f"morai_msgs-{profile}.json").read_text())
