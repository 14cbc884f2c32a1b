"""The ROS standard types egosim uses match Debian's generated modules."""

from __future__ import annotations

import json

import pytest

from egosim.msgs import get_profile
from tests.contract import PROTOCOL_DIR


def standard_contract() -> dict:
    return json.loads((PROTOCOL_DIR / "std_msgs_used.json").read_text())["types"]


@pytest.mark.parametrize("name", sorted(standard_contract()))
def test_standard_type_md5_equals_debian(name: str) -> None:
    assert get_profile().message(name).md5sum == standard_contract()[name]["md5sum"]
