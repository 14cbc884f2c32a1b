"""SetTrafficLight and IntersectionControl semantics, and the governing light query."""

import pytest

from egosim.world.map import build_builtin_map
from egosim.world.signals import (
    GREEN,
    GREEN_LEFT,
    OFF,
    RED,
    YELLOW,
    TrafficSignals,
    UnknownIntersectionError,
    UnknownLightError,
    UnsupportedAspectError,
    governing_light_id,
)

TOWN = build_builtin_map("town")


def _run(signals: TrafficSignals, seconds: float) -> None:
    for _ in range(round(seconds / 0.01)):
        signals.step(0.01)


def test_override_holds_through_phase_changes_until_released() -> None:
    signals = TrafficSignals(TOWN)
    signals.set_light("TL6_N", GREEN | GREEN_LEFT)
    _run(signals, 200.0)
    state = signals.light("TL6_N")
    assert (state.aspect, state.overridden) == (GREEN | GREEN_LEFT, True)
    signals.release_light("TL6_N")
    released = signals.light("TL6_N")
    assert released.aspect == signals.controller(6).aspect("TL6_N")
    assert not released.overridden


def test_status_off_switches_a_light_dark() -> None:
    signals = TrafficSignals(TOWN)
    signals.set_light("TL1_E", OFF)
    assert signals.light("TL1_E").aspect == OFF


def test_aspects_a_head_has_no_lamps_for_are_refused() -> None:
    signals = TrafficSignals(TOWN)
    with pytest.raises(UnsupportedAspectError):
        signals.set_light("TL17_E", GREEN)  # a flashing-yellow head
    with pytest.raises(UnsupportedAspectError):
        signals.set_light("TL5_N", 2)  # no lamp has bit 2
    with pytest.raises(UnknownLightError):
        signals.set_light("TL99_X", RED)
    assert not signals.light("TL17_E").overridden


def test_intersection_control_jumps_and_releases_its_lights() -> None:
    signals = TrafficSignals(TOWN)
    signals.set_light("TL6_E", YELLOW)
    signals.set_light("TL7_E", YELLOW)
    signals.control_intersection(6, 9, 3.0)
    status = signals.intersection_status(6)
    assert (status.phase_index, status.elapsed_s) == (9, pytest.approx(3.0))
    assert signals.light("TL6_N").aspect == GREEN  # phase 9: N/S green
    assert signals.light("TL6_E").aspect == RED
    assert not signals.light("TL6_E").overridden
    assert signals.light("TL7_E").overridden  # another intersection keeps its override
    with pytest.raises(UnknownIntersectionError):
        signals.control_intersection(999, 0, 0.0)


def test_configure_resets_programs_and_overrides() -> None:
    signals = TrafficSignals(TOWN)
    signals.set_light("TL6_E", YELLOW)
    _run(signals, 17.0)
    signals.configure()
    assert not signals.light("TL6_E").overridden
    assert signals.intersection_status(6).phase_index == 0


def test_governing_light_is_the_one_ahead_on_the_lane() -> None:
    lane = TOWN.lanes["R5_E_1"]
    x, y, _, _ = TOWN.pose_at("R5_E_1", 10.0)
    assert governing_light_id(TOWN, "R5_E_1", 10.0, x, y) == "TL7_W"
    # Past the stop line the next junction's light (R6_E_1 ends at junction 8) governs.
    past = lane.stop_line_s + 1.0
    x, y, _, _ = TOWN.pose_at("R5_E_1", past)
    assert governing_light_id(TOWN, "R5_E_1", past, x, y) == "TL8_W"
