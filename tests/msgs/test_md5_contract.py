"""Every morai_msgs type's md5 and definition equal the public contract's, in every release."""

from __future__ import annotations

import re

import pytest

from egosim.msgs import PROFILES, get_profile
from tests.contract import load_contract

# 24.r2 declares the non-ROS type `uint` in these; egosim serves the 26.r1 definitions.
SERVED_FROM_26R1 = {
    "24.r2": {"morai_msgs/MultiEgoSetting", "morai_msgs/NpcGhostInfo", "morai_msgs/NpcGhostCmd"}
}


def contract_messages(profile: str) -> list[str]:
    return sorted(load_contract(profile)["messages"])


def contract_services(profile: str) -> list[str]:
    return sorted(load_contract(profile)["services"])


def every(kind) -> list[tuple[str, str]]:
    return [(profile, name) for profile in PROFILES for name in kind(profile)]


@pytest.mark.parametrize("profile", PROFILES)
def test_profile_ships_exactly_the_contract_types(profile: str) -> None:
    own = [n for n in get_profile(profile).message_names() if n.startswith("morai_msgs/")]
    expected = set(contract_messages(profile)) | SERVED_FROM_26R1.get(profile, set())
    assert own == sorted(expected)
    assert get_profile(profile).service_names() == contract_services(profile)


@pytest.mark.parametrize(("profile", "name"), every(contract_messages))
def test_message_md5_equals_contract(profile: str, name: str) -> None:
    expected = load_contract(profile)["messages"][name]["md5sum"]
    assert get_profile(profile).message(name).md5sum == expected


@pytest.mark.parametrize("name", sorted(SERVED_FROM_26R1["24.r2"]))
def test_unbuildable_24r2_types_are_served_as_26r1(name: str) -> None:
    assert get_profile("24.r2").message(name).md5sum == get_profile("26.r1").message(name).md5sum


@pytest.mark.parametrize(("profile", "name"), every(contract_services))
def test_service_md5s_equal_contract(profile: str, name: str) -> None:
    contract = load_contract(profile)["services"][name]
    service = get_profile(profile).service(name)
    assert service.md5sum == contract["md5sum"]
    assert service.request.md5sum == contract["request_md5sum"]
    assert service.response.md5sum == contract["response_md5sum"]
    assert service.request.name == contract["request"]
    assert service.response.name == contract["response"]


def declarations(text: str) -> list[str]:
    """The declaration lines of one definition section, comments and blanks dropped."""
    lines = (re.sub(r"#.*", "", line).strip() for line in text.splitlines())
    return [" ".join(line.split()) for line in lines if line]


@pytest.mark.parametrize(("profile", "name"), every(contract_messages))
def test_definition_declares_contract_fields_and_dependencies(profile: str, name: str) -> None:
    contract = load_contract(profile)["messages"][name]
    sections = get_profile(profile).message(name).definition.split("=" * 80 + "\n")
    expected = [f"{t} {n}={v}" for t, n, v in contract["constants"]]
    expected += [f"{t} {n}" for t, n in contract["fields"]]
    assert declarations(sections[0]) == expected
    nested = [section.splitlines()[0] for section in sections[1:]]
    assert nested == [f"MSG: {dep}" for dep in contract["depends"]]
