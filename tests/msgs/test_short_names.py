"""A type may be named without its package when that name is unambiguous."""

from __future__ import annotations

import pytest

from egosim.msgs import UnknownTypeError, get_profile
from egosim.msgs.profile import resolve_short_name


@pytest.mark.parametrize(
    ("short", "full"),
    [
        ("CtrlCmd", "morai_msgs/CtrlCmd"),
        ("MoraiEventCmdSrv", "morai_msgs/MoraiEventCmdSrv"),
        ("Header", "std_msgs/Header"),
        ("Time", "std_msgs/Time"),  # rosbags' builtin_interfaces/Time is not a ROS 1 type
        ("PoseStamped", "geometry_msgs/PoseStamped"),
        ("morai_msgs/CtrlCmd", "morai_msgs/CtrlCmd"),
    ],
)
def test_short_names_resolve(short: str, full: str) -> None:
    assert get_profile("26.r1").resolve(short) == full


def test_service_halves_are_not_offered_as_types() -> None:
    with pytest.raises(UnknownTypeError) as error:
        get_profile("26.r1").resolve("EventCmd")
    assert "did you mean morai_msgs/MoraiEventCmdSrv, " in str(error.value)
    assert "Request" not in str(error.value)


def test_a_name_in_two_packages_is_ambiguous_and_lists_both() -> None:
    names = ["a_msgs/Status", "b_msgs/Status", "a_msgs/Other"]
    with pytest.raises(
        UnknownTypeError, match="'Status' is ambiguous in p: a_msgs/Status, b_msgs/Status"
    ):
        resolve_short_name("Status", names, "p")
    assert resolve_short_name("Other", names, "p") == "a_msgs/Other"
