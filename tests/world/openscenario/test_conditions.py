"""Conditions fire where their closed forms say: speeds, accelerations and relative
speeds of an accelerating car, the position it reaches and its distance to a point
(longitudinal and lateral), the end of a road, time off the road, a light's state, and
the parameters and variables the storyboard sets."""

from __future__ import annotations

import math

import pytest
from tests.world.openscenario.stories import (
    DT,
    event,
    init_speed,
    lane,
    scenario,
    speed_action,
    start,
    start_world,
    story,
    teleport,
    time_is,
    vehicle,
)
from tests.world.openscenario.test_signal_controllers import PHASES, junction, with_controllers

FLAG = '<VariableDeclaration name="fired" variableType="boolean" value="false"/>'
FIRE = """<GlobalAction><VariableAction variableRef="fired"><SetAction value="true"/>
  </VariableAction></GlobalAction>"""

# The car: 10 m/s from s = 150 on lane -1 (x = s), from 1 s on a linear speed change to
# 20 m/s over 4 s (2.5 m/s²); the ego at 8 m/s from s = 50.
CAR_START, CAR_SPEED, RISE_AT, ACCELERATION = 150.0, 10.0, 1.0, 2.5
EGO_SPEED = 8.0


def car_x(t: float) -> float:
    """The car's position at t <= 5 s (exact: a step moves by its mean speed)."""
    late = max(t - RISE_AT, 0.0)
    return CAR_START + CAR_SPEED * t + ACCELERATION * late**2 / 2.0


def when_car_reaches(x: float) -> float:
    """The time (within the speed change) the car's reference point reaches x."""
    u = -CAR_SPEED + math.sqrt(CAR_SPEED**2 + 2 * ACCELERATION * (x - car_x(RISE_AT)))
    return RISE_AT + u / ACCELERATION


def by_entity(body: str, who: str = "Car") -> str:
    return f"""<Condition name="c" delay="0" conditionEdge="none"><ByEntityCondition>
      <TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="{who}"/>
        </TriggeringEntities>
      <EntityCondition>{body}</EntityCondition></ByEntityCondition></Condition>"""


def by_value(body: str) -> str:
    return f"""<Condition name="c" delay="0" conditionEdge="none"><ByValueCondition>{body}
      </ByValueCondition></Condition>"""


def accelerating_car(watch: str) -> str:
    rise = event(
        "Rise", speed_action(20, "linear", "time", 4), start(time_is(RISE_AT, "greaterOrEqual"))
    )
    seen = event("Seen", FIRE, start(watch), "parallel")
    return scenario(
        vehicle("Ego") + vehicle("Car"),
        teleport("Ego", lane(50))
        + init_speed("Ego", EGO_SPEED)
        + teleport("Car", lane(CAR_START))
        + init_speed("Car", CAR_SPEED),
        story("Car", rise, seen),
        variables=FLAG,
    )


def fired_at(text: str, seconds: float, **world: object) -> float | None:
    """Scenario time of the step whose evaluation first held (None: never within
    `seconds`)."""
    run_world, run = start_world(text, **world)  # type: ignore[arg-type]
    for _ in range(round(seconds / DT)):
        before = run.rt.time
        run.step(DT, True)
        run_world.step(DT)
        if run.rt.variables["fired"] is True:
            return before
    return None


@pytest.mark.parametrize(
    ("body", "expected"),
    [
        # 10 + 2.5 (t - 1) > 15
        ('<SpeedCondition value="15" rule="greaterThan"/>', RISE_AT + 5.0 / ACCELERATION),
        # The speed change's 2.5 m/s² from its first step on.
        ('<AccelerationCondition value="2" rule="greaterThan"/>', RISE_AT),
        # (10 + 2.5 (t - 1)) - 8 > 5
        (
            '<RelativeSpeedCondition entityRef="Ego" value="5" rule="greaterThan"/>',
            RISE_AT + (5.0 - (CAR_SPEED - EGO_SPEED)) / ACCELERATION,
        ),
        # Within 1 m of s = 200: the car's reference point at 199.
        (
            '<ReachPositionCondition tolerance="1"><Position>'
            + lane(200)
            + "</Position></ReachPositionCondition>",
            when_car_reaches(199.0),
        ),
        # Reference points 20 m apart along the car's heading: at 210.
        (
            '<DistanceCondition value="20" freespace="false" rule="lessThan" '
            'relativeDistanceType="longitudinal" coordinateSystem="entity"><Position>'
            + lane(230)
            + "</Position></DistanceCondition>",
            when_car_reaches(210.0),
        ),
        # The car's box (front 3.5 m ahead of its reference) 20 m from the point: at 206.5.
        (
            '<DistanceCondition value="20" freespace="true" rule="lessThan" '
            'relativeDistanceType="euclidianDistance" coordinateSystem="entity"><Position>'
            + lane(230)
            + "</Position></DistanceCondition>",
            when_car_reaches(206.5),
        ),
        # A point on lane -2 (3.5 m to the car's right): laterally 3.5 m from the start,
        # however far ahead it is.
        (
            '<DistanceCondition value="3.6" freespace="false" rule="lessThan" '
            'relativeDistanceType="lateral" coordinateSystem="entity"><Position>'
            + lane(600, -2)
            + "</Position></DistanceCondition>",
            0.0,
        ),
        (
            '<DistanceCondition value="3.4" freespace="false" rule="lessThan" '
            'relativeDistanceType="lateral" coordinateSystem="entity"><Position>'
            + lane(600, -2)
            + "</Position></DistanceCondition>",
            None,
        ),
    ],
)
def test_entity_conditions_fire_at_their_closed_forms(body: str, expected: float | None) -> None:
    at = fired_at(accelerating_car(by_entity(body)), 4.5)
    if expected is None:
        assert at is None
    else:
        # A strict rule first holds in the step after the crossing.
        assert at == pytest.approx(expected, abs=DT + 1e-9)


def test_the_end_of_the_road_counts_from_where_the_car_stops() -> None:
    # The highway ends at s = 1000: from s = 960 at 20 m/s the car is there at 2 s and
    # stops; a second later the condition holds.
    watch = by_entity('<EndOfRoadCondition duration="1"/>')
    text = scenario(
        vehicle("Ego") + vehicle("Car"),
        teleport("Ego", lane(50)) + teleport("Car", lane(960)) + init_speed("Car", 20.0),
        story("Car", event("Seen", FIRE, start(watch))),
        variables=FLAG,
    )
    assert fired_at(text, 4.0) == pytest.approx(3.0, abs=3 * DT)


def test_time_off_the_road_counts_for_the_entity_off_it_only() -> None:
    # The highway's four lanes cover |y| <= 7 m.
    text = scenario(
        vehicle("Ego") + vehicle("Car") + vehicle("Parked"),
        teleport("Ego", lane(50))
        + teleport("Car", lane(150))
        + teleport("Parked", '<WorldPosition x="300" y="30" h="0"/>'),
        story(
            "Car",
            event("OnRoad", FIRE, start(by_entity('<OffroadCondition duration="0.2"/>'))),
            event(
                "OffRoad",
                FIRE.replace('"fired"', '"off"'),
                start(by_entity('<OffroadCondition duration="1.5"/>', "Parked")),
                "parallel",
            ),
        ),
        variables=FLAG + FLAG.replace('"fired"', '"off"'),
    )
    world, run = start_world(text)
    off_at = None
    for _ in range(round(3.0 / DT)):
        before = run.rt.time
        run.step(DT, True)
        world.step(DT)
        if off_at is None and run.rt.variables["off"] is True:
            off_at = before
    assert off_at == pytest.approx(1.5, abs=2 * DT)
    assert run.rt.variables["fired"] is False  # the car on its lane never is off the road


@pytest.mark.parametrize(
    ("state", "expected"),
    [("off;on;off", 10.0), ("yellow", 10.0), ("red", 13.0), ("on;off;off", 13.0)],
)
def test_a_light_condition_holds_when_the_light_shows_its_state(
    state: str, expected: float
) -> None:
    # TL1's controller: green for 10 s, yellow for 3, red for 12.
    watch = by_value(f'<TrafficSignalCondition name="TL1" state="{state}"/>')
    text = with_controllers(
        f'<TrafficSignalController name="North">{PHASES}</TrafficSignalController>',
        story("Ego", event("Seen", FIRE, start(watch))),
        variables=FLAG,
    )
    assert fired_at(text, 15.0, lane_map=junction()) == pytest.approx(expected, abs=2 * DT)


def test_parameter_and_variable_conditions_see_the_values_actions_set() -> None:
    # 1.0's ParameterAction sets 5 at 1 s and adds 2 at 2 s (7); 1.2's VariableAction
    # multiplies 3 by 4 at 3 s (12). Each condition's event fires when its value is there.
    def set_value(kind: str, name: str, rule: str) -> str:
        ref = "parameterRef" if kind == "Parameter" else "variableRef"
        return f"""<GlobalAction><{kind}Action {ref}="{name}">{rule}</{kind}Action>
          </GlobalAction>"""

    def watch(kind: str, name: str, value: str) -> str:
        ref = "parameterRef" if kind == "Parameter" else "variableRef"
        return by_value(f'<{kind}Condition {ref}="{name}" value="{value}" rule="equalTo"/>')

    def mark(flag: str) -> str:
        return FIRE.replace('"fired"', f'"{flag}"')

    events = [
        event("Set", set_value("Parameter", "Gap", '<SetAction value="5"/>'), start(time_is(1.0))),
        event(
            "Add",
            set_value(
                "Parameter",
                "Gap",
                '<ModifyAction><Rule><AddValue value="2"/></Rule></ModifyAction>',
            ),
            start(time_is(2.0)),
        ),
        event(
            "Times",
            set_value(
                "Variable",
                "Count",
                '<ModifyAction><Rule><MultiplyByValue value="4"/></Rule></ModifyAction>',
            ),
            start(time_is(3.0)),
        ),
        event("SawFive", mark("five"), start(watch("Parameter", "Gap", "5"))),
        event("SawSeven", mark("seven"), start(watch("Parameter", "Gap", "7"))),
        event("SawTwelve", mark("twelve"), start(watch("Variable", "Count", "12"))),
    ]
    flags = "".join(
        f'<VariableDeclaration name="{flag}" variableType="boolean" value="false"/>'
        for flag in ("five", "seven", "twelve")
    )
    text = scenario(
        vehicle("Ego"),
        teleport("Ego", lane(50)),
        story("Ego", *(e.replace('priority="override"', 'priority="parallel"') for e in events)),
        parameters='<ParameterDeclaration name="Gap" parameterType="double" value="0"/>',
        variables=flags + '<VariableDeclaration name="Count" variableType="double" value="3"/>',
        minor=2,
    )
    world, run = start_world(text)
    seen: dict[str, float] = {}
    for _ in range(round(4.0 / DT)):
        before = run.rt.time
        run.step(DT, True)
        world.step(DT)
        for flag in ("five", "seven", "twelve"):
            if flag not in seen and run.rt.variables[flag] is True:
                seen[flag] = before
    # A value set in one step is seen by the conditions of the next.
    assert seen == {
        "five": pytest.approx(1.0 + DT, abs=2 * DT),
        "seven": pytest.approx(2.0 + DT, abs=2 * DT),
        "twelve": pytest.approx(3.0 + DT, abs=2 * DT),
    }
    assert run.rt.parameters["Gap"] == 7.0 and run.rt.variables["Count"] == 12.0
