"""Every morai_msgs type's md5 and definition equal the public contract's."""

from __future__ import annotations

import re

import pytest

from egosim.msgs import get_profile
from tests.contract import load_contract

PROFILE = "26.r1"


def contract_messages() -> list[str]:
    return sorted(load_contract(PROFILE)["messages"])


def contract_services() -> list[str]:
    return sorted(load_contract(PROFILE)["services"])


def test_profile_ships_exactly_the_contract_types() -> None:
    profile = get_profile(PROFILE)
    own = [name for name in profile.message_names() if name.startswith("morai_msgs/")]
    assert own == contract_messages()
    assert profile.service_names() == contract_services()


@pytest.mark.parametrize("name", contract_messages())
def test_message_md5_equals_contract(name: str) -> None:
    assert (
        get_profile(PROFILE).message(name).md5sum
        == load_contract(PROFILE)["messages"][name]["md5sum"]
    )


@pytest.mark.parametrize("name", contract_services())
def test_service_md5s_equal_contract(name: str) -> None:
    contract = load_contract(PROFILE)["services"][name]
    service = get_profile(PROFILE).service(name)
    assert service.md5sum == contract["md5sum"]
    assert service.request.md5sum == contract["request_md5sum"]
    assert service.response.md5sum == contract["response_md5sum"]
    assert service.request.name == contract["request"]
    assert service.response.name == contract["response"]


def declarations(text: str) -> list[str]:
    """The declaration lines of one definition section, comments and blanks dropped."""
    lines = (re.sub(r"#.*", "", line).strip() for line in text.splitlines())
    return [" ".join(line.split()) for line in lines if line]


@pytest.mark.parametrize("name", contract_messages())
def test_definition_declares_contract_fields_and_dependencies(name: str) -> None:
    contract = load_contract(PROFILE)["messages"][name]
    sections = get_profile(PROFILE).message(name).definition.split("=" * 80 + "\n")
    expected = [f"{t} {n}={v}" for t, n, v in contract["constants"]]
    expected += [f"{t} {n}" for t, n in contract["fields"]]
    assert declarations(sections[0]) == expected
    nested = [section.splitlines()[0] for section in sections[1:]]
    assert nested == [f"MSG: {dep}" for dep in contract["depends"]]
