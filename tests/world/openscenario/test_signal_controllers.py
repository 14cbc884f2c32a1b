"""RoadNetwork's TrafficSignalControllers: phases cycle for their durations and set the
lights they name, delays shift a controller against its reference, the controller
action jumps to a phase and the condition sees it."""

from __future__ import annotations

from functools import cache
from pathlib import Path

from tests.world.openscenario.stories import (
    event,
    scenario,
    set_variable,
    start,
    start_world,
    step,
    story,
    teleport,
    time_is,
    vehicle,
)

from egosim.maps import load_map
from egosim.world.map import LaneMap
from egosim.world.signals.aspects import GREEN, RED, YELLOW

JUNCTION = Path(__file__).parents[2] / "data" / "maps" / "junction.xodr"
PHASES = """<Phase name="go" duration="10">
    <TrafficSignalState trafficSignalId="TL1" state="off;off;on"/>
    <TrafficSignalState trafficSignalId="TL2" state="on;off;off"/></Phase>
  <Phase name="caution" duration="3">
    <TrafficSignalState trafficSignalId="TL1" state="off;on;off"/></Phase>
  <Phase name="stop" duration="12">
    <TrafficSignalState trafficSignalId="TL1" state="on;off;off"/>
    <TrafficSignalState trafficSignalId="TL2" state="off;off;on"/></Phase>"""


@cache
def junction() -> LaneMap:
    return load_map(str(JUNCTION))


def with_controllers(controllers: str, stories: str = "", variables: str = "") -> str:
    text = scenario(
        vehicle("Ego"),
        teleport("Ego", '<WorldPosition x="0" y="0" h="0"/>'),
        stories,
        variables=variables,
    )
    return text.replace(
        '<RoadNetwork><LogicFile filepath="highway.xodr"/>',
        f'<RoadNetwork><LogicFile filepath="junction.xodr"/><TrafficSignals>{controllers}'
        "</TrafficSignals>",
    )


def aspects_over(text: str, seconds: float, every: float) -> list[tuple[int, int]]:
    world, run = start_world(text, lane_map=junction())
    seen = []
    step(world, run, every / 2.0)  # samples in the middle of each interval
    for _ in range(round(seconds / every)):
        seen.append((world.signals.light("TL1").aspect, world.signals.light("TL2").aspect))
        step(world, run, every)
    return seen


def test_phases_set_their_lights_for_their_durations_and_cycle() -> None:
    controller = f'<TrafficSignalController name="C1">{PHASES}</TrafficSignalController>'
    seen = aspects_over(with_controllers(controller), 30.0, 1.0)
    # Seconds 0-10 go, 10-13 caution (TL2 keeps the red of go), 13-25 stop, then go.
    assert seen[0] == seen[9] == (GREEN, RED)
    assert seen[10] == seen[12] == (YELLOW, RED)
    assert seen[13] == seen[24] == (RED, GREEN)
    assert seen[25] == (GREEN, RED)


def test_a_delay_to_the_reference_shifts_the_cycle() -> None:
    # C2 runs 4 s behind C1: at t = 0 it is 4 s before the end of its cycle (stop).
    controllers = (
        f'<TrafficSignalController name="C1">{PHASES.replace("TL1", "X").replace("TL2", "Y")}'
        f'</TrafficSignalController><TrafficSignalController name="C2" delay="4" '
        f'reference="C1">{PHASES}</TrafficSignalController>'
    )
    world, run = start_world(with_controllers(controllers), lane_map=junction())
    notes = step(world, run, 0.5)
    assert world.signals.light("TL1").aspect == RED
    step(world, run, 4.0)
    assert world.signals.light("TL1").aspect == GREEN
    assert any("'X'" in note for note in notes), notes


def test_the_controller_action_jumps_to_a_phase_and_the_condition_sees_it() -> None:
    controller = f'<TrafficSignalController name="C1">{PHASES}</TrafficSignalController>'
    in_stop = """<Condition name="c" delay="0" conditionEdge="none"><ByValueCondition>
      <TrafficSignalControllerCondition trafficSignalControllerRef="C1" phase="stop"/>
      </ByValueCondition></Condition>"""
    jump = """<GlobalAction><InfrastructureAction><TrafficSignalAction>
      <TrafficSignalControllerAction trafficSignalControllerRef="C1" phase="stop"/>
      </TrafficSignalAction></InfrastructureAction></GlobalAction>"""
    text = with_controllers(
        controller,
        story(
            "Ego",
            event("Jump", jump, start(time_is(2.0))),
            event("Seen", set_variable("fired", "true"), start(in_stop), priority="parallel"),
        ),
        variables='<VariableDeclaration name="fired" variableType="boolean" value="false"/>',
    )
    world, run = start_world(text, lane_map=junction())
    step(world, run, 2.005)
    assert world.signals.light("TL1").aspect == GREEN
    step(world, run, 0.03)
    assert world.signals.light("TL1").aspect == RED
    assert run.rt.variables["fired"] is True
    step(world, run, 12.0)  # 12 s of stop from the jump, then go
    assert world.signals.light("TL1").aspect == GREEN


def test_a_light_the_map_lacks_is_one_note() -> None:
    controller = (
        '<TrafficSignalController name="C1"><Phase name="p" duration="5">'
        '<TrafficSignalState trafficSignalId="nowhere" state="on;off;off"/></Phase>'
        "</TrafficSignalController>"
    )
    world, run = start_world(with_controllers(controller), lane_map=junction())
    notes = step(world, run, 12.0)
    assert len([n for n in notes if "nowhere" in n]) == 1, notes
