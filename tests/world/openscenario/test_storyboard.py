"""The storyboard's state machine and its triggers: edges, delays, priorities, execution
counts, element states, stop triggers, and conditions that fire where they say."""

from __future__ import annotations

import pytest
from tests.world.openscenario.stories import (
    DT,
    event,
    init_speed,
    lane,
    scenario,
    set_variable,
    speed_action,
    start,
    start_world,
    step,
    story,
    teleport,
    time_is,
    vehicle,
)

COUNTER = '<VariableDeclaration name="n" variableType="double" value="0"/>'
FLAG = '<VariableDeclaration name="fired" variableType="boolean" value="false"/>'
ADD_ONE = """<GlobalAction><VariableAction variableRef="n"><ModifyAction><Rule>
  <AddValue value="1"/></Rule></ModifyAction></VariableAction></GlobalAction>"""


def cars(stories: str, stop: str = "", variables: str = "", init: str = "") -> str:
    return scenario(
        vehicle("Ego") + vehicle("Car"),
        teleport("Ego", lane(50)) + teleport("Car", lane(150)) + init,
        stories,
        stop,
        variables=variables,
    )


def fired_at(world, run, seconds: float, name: str = "fired"):  # type: ignore[no-untyped-def]
    """Scenario time at which the variable became true (None if it did not)."""
    for _ in range(round(seconds / DT)):
        run.step(DT, True)
        world.step(DT)
        if run.rt.variables[name] is True:
            return run.rt.time - DT
    return None


def test_a_time_headway_trigger_fires_at_the_headway_it_states() -> None:
    headway = """<Condition name="h" delay="0" conditionEdge="none"><ByEntityCondition>
      <TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="Ego"/>
        </TriggeringEntities>
      <EntityCondition><TimeHeadwayCondition entityRef="Car" value="2" freespace="true"
        rule="lessThan" coordinateSystem="entity" relativeDistanceType="longitudinal"/>
          </EntityCondition>
    </ByEntityCondition></Condition>"""
    text = cars(
        story("Car", event("E", set_variable("fired", "true"), start(headway))),
        variables=FLAG,
        init=init_speed("Ego", 20.0),
    )
    world, run = start_world(text)
    ego, car = run.rt.entity("Ego"), run.rt.entity("Car")
    gap = (car.box_centre()[0] - 2.0) - (ego.box_centre()[0] + 2.0)
    # 20 m/s closing on a standing car: 2 s of headway is 40 m of gap.
    expected = (gap - 40.0) / 20.0
    assert fired_at(world, run, 5.0) == pytest.approx(expected, abs=DT + 1e-9)


def test_a_condition_delay_shifts_its_result() -> None:
    text = cars(
        story("Car", event("E", set_variable("fired", "true"), start(time_is(1.0, delay=0.5)))),
        variables=FLAG,
    )
    world, run = start_world(text)
    # Scenario time sums the steps: a threshold is crossed within one step of it.
    assert fired_at(world, run, 3.0) == pytest.approx(1.5, abs=DT + 1e-9)


@pytest.mark.parametrize(
    ("edge", "rule", "expected"),
    [("rising", "greaterThan", 1.0), ("falling", "lessThan", 1.0), ("none", "lessThan", 0.0)],
)
def test_condition_edges(edge: str, rule: str, expected: float) -> None:
    text = cars(
        story("Car", event("E", set_variable("fired", "true"), start(time_is(1.0, rule, edge)))),
        variables=FLAG,
    )
    world, run = start_world(text)
    assert fired_at(world, run, 3.0) == pytest.approx(expected, abs=DT + 1e-9)


def test_a_rising_edge_needs_a_change_a_condition_true_from_the_start_never_rises() -> None:
    text = cars(
        story(
            "Car", event("E", set_variable("fired", "true"), start(time_is(-1.0, edge="rising")))
        ),
        variables=FLAG,
    )
    world, run = start_world(text)
    assert fired_at(world, run, 1.0) is None


def test_override_stops_the_running_event_skip_waits_parallel_runs_alongside() -> None:
    slow = event(
        "Slow", speed_action(5, "linear", "time", 10), start(time_is(0.0, "greaterOrEqual"))
    )
    fast = event("Fast", speed_action(20, "linear", "time", 1), start(time_is(1.0)), "override")
    world, run = start_world(cars(story("Car", slow, fast)))
    step(world, run, 1.5)
    elements = run.rt.elements
    assert elements[("event", "Slow")].state == "completeState"
    assert any(name == "stopTransition" for _, name in elements[("event", "Slow")].transitions)
    step(world, run, 1.0)
    assert run.rt.entity("Car").speed == pytest.approx(20.0)

    skipped = event("Late", set_variable("fired", "true"), start(time_is(1.0)), "skip")
    world, run = start_world(cars(story("Car", slow, skipped), variables=FLAG))
    step(world, run, 2.0)
    assert run.rt.elements[("event", "Late")].state == "standbyState"
    assert run.rt.variables["fired"] is False
    assert any(n == "skipTransition" for _, n in run.rt.elements[("event", "Late")].transitions)

    parallel = event("Also", set_variable("fired", "true"), start(time_is(1.0)), "parallel")
    world, run = start_world(cars(story("Car", slow, parallel), variables=FLAG))
    step(world, run, 2.0)
    assert run.rt.variables["fired"] is True
    assert run.rt.elements[("event", "Slow")].state == "runningState"


def test_execution_counts_of_events_and_maneuver_groups() -> None:
    again = event("Count", ADD_ONE, start(time_is(0.0, "greaterOrEqual")), count=3)
    world, run = start_world(cars(story("Car", again), variables=COUNTER))
    step(world, run, 1.0)
    assert run.rt.variables["n"] == 3.0

    once = event("Count", ADD_ONE, start(time_is(0.0, "greaterOrEqual")))
    world, run = start_world(cars(story("Car", once, executions=4), variables=COUNTER))
    step(world, run, 1.0)
    assert run.rt.variables["n"] == 4.0
    assert run.rt.elements[("maneuverGroup", "G")].state == "completeState"


def test_an_act_waits_for_its_start_trigger_and_the_stop_trigger_ends_everything() -> None:
    act_start = "<StartTrigger><ConditionGroup>" + time_is(2.0) + "</ConditionGroup></StartTrigger>"
    stop = time_is(3.0)
    text = cars(
        story("Car", event("E", speed_action(10, "linear", "time", 5)), act_trigger=act_start),
        stop=stop,
    )
    world, run = start_world(text)
    step(world, run, 2.0)
    assert run.rt.elements[("act", "A")].state == "standbyState"
    step(world, run, 0.5)
    assert run.rt.elements[("act", "A")].state == "runningState"
    assert not run.finished
    step(world, run, 1.0)
    assert run.finished
    assert run.outcome().state == "stopped"
    assert run.rt.elements[("action", "EAction")].state == "completeState"
    speed = run.rt.entity("Car").speed
    step(world, run, 1.0)
    assert run.rt.entity("Car").speed == speed  # nothing moves after the end


def test_storyboard_element_state_conditions_see_states_and_transitions() -> None:
    first = event("First", speed_action(3, "linear", "time", 1), start(time_is(0.5)))
    watch = """<Condition name="c" delay="0" conditionEdge="none"><ByValueCondition>
      <StoryboardElementStateCondition storyboardElementType="event" storyboardElementRef="First"
        state="endTransition"/></ByValueCondition></Condition>"""
    second = event("Second", set_variable("fired", "true"), start(watch), "parallel")
    world, run = start_world(cars(story("Car", first, second), variables=FLAG))
    assert fired_at(world, run, 3.0) == pytest.approx(1.5 + DT, abs=2 * DT)


def test_collision_standstill_and_travelled_distance_conditions() -> None:
    def entity_condition(body: str, who: str = "Car") -> str:
        return f"""<Condition name="c" delay="0" conditionEdge="none"><ByEntityCondition>
          <TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="{who}"/>
            </TriggeringEntities>
          <EntityCondition>{body}</EntityCondition></ByEntityCondition></Condition>"""

    crash = entity_condition(
        '<CollisionCondition><EntityRef entityRef="Ego"/></CollisionCondition>'
    )
    text = cars(
        story("Car", event("E", set_variable("fired", "true"), start(crash))),
        variables=FLAG,
        init=init_speed("Ego", 10.0),
    )
    world, run = start_world(text)
    ego, car = run.rt.entity("Ego"), run.rt.entity("Car")
    gap = (car.box_centre()[0] - 2.0) - (ego.box_centre()[0] + 2.0)
    assert fired_at(world, run, 12.0) == pytest.approx(gap / 10.0, abs=2 * DT)

    travelled = entity_condition('<TraveledDistanceCondition value="25"/>', "Ego")
    text = cars(
        story("Car", event("E", set_variable("fired", "true"), start(travelled))),
        variables=FLAG,
        init=init_speed("Ego", 10.0),
    )
    world, run = start_world(text)
    assert fired_at(world, run, 5.0) == pytest.approx(2.5, abs=2 * DT)

    still = entity_condition('<StandStillCondition duration="1.5"/>')
    world, run = start_world(
        cars(story("Car", event("E", set_variable("fired", "true"), start(still))), variables=FLAG)
    )
    assert fired_at(world, run, 3.0) == pytest.approx(1.5, abs=2 * DT)
