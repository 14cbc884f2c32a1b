"""Phase programs cycle with their configured durations; IntersectionStatus reports them."""

import pytest

from egosim.world.map import build_builtin_map
from egosim.world.signals import (
    GREEN,
    GREEN_LEFT,
    OFF,
    RED,
    YELLOW,
    IntersectionProgram,
    LightType,
    PhaseTiming,
    TrafficSignals,
    UnknownPhaseError,
    can_show,
)
from egosim.world.signals.phases import build_program

TOWN = build_builtin_map("town")
TIMING = PhaseTiming(green_s=7.0, left_s=4.0, yellow_s=2.0, all_red_s=1.0, flash_s=0.5)
STEP_S = 0.01


def _signals(**programs: IntersectionProgram) -> TrafficSignals:
    return TrafficSignals(
        TOWN, {int(k[1:]): p for k, p in programs.items()}, IntersectionProgram(TIMING)
    )


def _run(signals: TrafficSignals, seconds: float) -> None:
    for _ in range(round(seconds / STEP_S)):
        signals.step(STEP_S)


def test_protected_left_program_of_a_downtown_junction() -> None:
    # Junction 6: type 2 heads, groups (E, W) and (N, S).
    controller = _signals().controller(6)
    assert controller.light_ids == ("TL6_E", "TL6_N", "TL6_W", "TL6_S")
    program = [(p.duration_s, p.aspects) for p in controller.program]
    left, go = RED | GREEN_LEFT, GREEN
    assert program == [
        (4.0, (left, RED, left, RED)),
        (2.0, (YELLOW, RED, YELLOW, RED)),
        (1.0, (RED,) * 4),
        (7.0, (go, RED, go, RED)),
        (2.0, (YELLOW, RED, YELLOW, RED)),
        (1.0, (RED,) * 4),
        (4.0, (RED, left, RED, left)),
        (2.0, (RED, YELLOW, RED, YELLOW)),
        (1.0, (RED,) * 4),
        (7.0, (RED, go, RED, go)),
        (2.0, (RED, YELLOW, RED, YELLOW)),
        (1.0, (RED,) * 4),
    ]


def test_an_approach_alone_goes_through_and_left_together_on_a_standard_junction() -> None:
    # Junction 2 (not downtown): each approach with a left arrow is served alone.
    controller = _signals().controller(2)
    types = [TOWN.traffic_lights[i].light_type for i in controller.light_ids]
    go_phases = [p for p in controller.program if p.name.endswith(" go")]
    assert len(go_phases) == len(controller.light_ids)
    for phase in go_phases:
        lit = [(t, a) for t, a in zip(types, phase.aspects, strict=True) if a != RED]
        assert lit in ([(LightType.RYG_LEFT_GREEN, GREEN | GREEN_LEFT)], [(LightType.RYG, GREEN)])


def test_a_left_arrow_head_shows_only_its_arrow_and_waits_out_the_through_phase() -> None:
    # One group: a left-turn head (R/Y/left arrow), a plain head, a four-lamp head.
    types = {"L": LightType.RYG_LEFT, "P": LightType.RYG, "F": LightType.RYG_LEFT_GREEN}
    program = build_program(["L", "P", "F"], types, [("L", "P", "F")], TIMING)
    assert [(p.duration_s, p.aspects) for p in program] == [
        (4.0, (GREEN_LEFT, RED, RED | GREEN_LEFT)),
        (2.0, (YELLOW, RED, YELLOW)),
        (1.0, (RED,) * 3),
        (7.0, (RED, GREEN, GREEN)),
        (2.0, (RED, YELLOW, YELLOW)),
        (1.0, (RED,) * 3),
    ]
    for phase in program:
        for light_id, aspect in zip("LPF", phase.aspects, strict=True):
            assert can_show(types[light_id], aspect)


def test_a_left_arrow_head_alone_in_its_group_gets_the_left_phase_time() -> None:
    program = build_program(["L"], {"L": LightType.RYG_LEFT}, [("L",)], TIMING)
    assert [(p.duration_s, p.aspects) for p in program] == [
        (4.0, (GREEN_LEFT,)),
        (2.0, (YELLOW,)),
        (1.0, (RED,)),
    ]


def test_every_aspect_of_every_program_fits_its_head() -> None:
    signals = _signals()
    for controller in signals.controllers.values():
        for phase in controller.program:
            for light_id, aspect in zip(controller.light_ids, phase.aspects, strict=True):
                assert can_show(TOWN.traffic_lights[light_id].light_type, aspect)


def test_status_reports_phase_and_elapsed_time_through_a_cycle() -> None:
    signals = _signals()
    controller = signals.controller(6)
    starts = [0.0]
    for phase in controller.program:
        starts.append(starts[-1] + phase.duration_s)
    cycle = starts[-1]
    for probe in (0.5, 4.5, 6.2, 13.9, 21.3, cycle - 0.25, cycle + 3.0):
        fresh = _signals()
        _run(fresh, probe)
        status = fresh.intersection_status(6)
        in_cycle = probe % cycle
        expected = max(k for k, start in enumerate(starts[:-1]) if start <= in_cycle + 1e-9)
        assert status.intersection_id == 6
        assert status.phase_index == expected
        assert status.elapsed_s == pytest.approx(in_cycle - starts[expected], abs=1e-6)


def test_light_aspects_follow_the_phase() -> None:
    signals = _signals()
    _run(signals, 7.5)  # 4 left + 2 yellow + 1 all red, 0.5 s into E/W green
    assert signals.light("TL6_E").aspect == GREEN
    assert signals.light("TL6_N").aspect == RED


def test_flashing_junction_blinks_with_its_half_period() -> None:
    signals = _signals()
    assert signals.light("TL17_E").aspect == YELLOW
    _run(signals, 0.75)
    assert signals.light("TL17_E").aspect == OFF
    _run(signals, 0.5)
    assert signals.light("TL17_E").aspect == YELLOW


def test_initial_phase_and_time_from_the_program() -> None:
    signals = _signals(j6=IntersectionProgram(TIMING, initial_phase=3, initial_elapsed_s=2.5))
    status = signals.intersection_status(6)
    assert (status.phase_index, status.elapsed_s) == (3, pytest.approx(2.5))
    with pytest.raises(UnknownPhaseError):
        _signals(j6=IntersectionProgram(TIMING, initial_phase=12))
