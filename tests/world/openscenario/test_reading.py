"""Reading OpenSCENARIO files: expressions, parameters and their constraints, catalogues
with parameter assignments, the ego's choice, and what is reported: an unsupported
element as one line naming it and its file:line, a mistake as a ScenarioError there."""

from __future__ import annotations

import math

import pytest
from tests.world.openscenario.stories import (
    event,
    lane,
    scenario,
    start,
    start_world,
    step,
    story,
    teleport,
    time_is,
    vehicle,
)

from egosim.world.openscenario import read_openscenario
from egosim.world.openscenario.expressions import ExpressionError, evaluate
from egosim.world.scenario import ScenarioError


def values(name: str) -> float | bool | str:
    return {"a": 2.0, "b": 3.0, "flag": True}[name]


@pytest.mark.parametrize(
    ("expression", "value"),
    [
        ("$a + $b * 2", 8.0),
        ("($a + $b) * 2", 10.0),
        ("-$a ^ 2" if False else "-$a * 2", -4.0),
        ("$b % $a", 1.0),
        ("pow($a, $b) + sqrt(16)", 12.0),
        ("max($a, $b) - min($a, $b) + abs(-1) + sign(-3)", 1.0),
        ("round(2.5) + floor(2.7) + ceil(2.1)", 8.0),
        ("$a < $b and not ($a == $b)", True),
        ("$a >= $b or $flag", True),
        ("sin(pi / 2) + cos(0)", 2.0),
    ],
)
def test_expressions(expression: str, value: object) -> None:
    assert evaluate(expression, values) == pytest.approx(value)


@pytest.mark.parametrize("expression", ["$a +", "__import__('os')", "$nope", "$a / 0", "[1]"])
def test_bad_expressions_are_errors_not_tracebacks(expression: str) -> None:
    with pytest.raises(ExpressionError):
        evaluate(expression, lambda name: values(name) if name != "nope" else _missing())


def _missing() -> float:
    raise ExpressionError("no parameter 'nope'")


PARAMETERS = """
  <ParameterDeclaration name="Speed_kph" parameterType="double" value="36"/>
  <ParameterDeclaration name="_Speed" parameterType="double" value="${$Speed_kph / 3.6}"/>
  <ParameterDeclaration name="Lane" parameterType="int" value="-1">
    <ConstraintGroup><ValueConstraint rule="equalTo" value="-1"/></ConstraintGroup>
    <ConstraintGroup><ValueConstraint rule="equalTo" value="-2"/></ConstraintGroup>
  </ParameterDeclaration>
  <ParameterDeclaration name="Start" parameterType="double" value="80">
    <ConstraintGroup><ValueConstraint rule="greaterOrEqual" value="10"/>
      <ValueConstraint rule="lessThan" value="900"/></ConstraintGroup>
  </ParameterDeclaration>"""


def parameter_scenario() -> str:
    car = teleport("Ego", '<LanePosition roadId="1" laneId="$Lane" s="$Start"/>')
    speed = """<Private entityRef="Ego"><PrivateAction><LongitudinalAction><SpeedAction>
      <SpeedActionDynamics dynamicsShape="step" value="0" dynamicsDimension="time"/>
      <SpeedActionTarget><AbsoluteTargetSpeed value="$_Speed"/></SpeedActionTarget>
    </SpeedAction></LongitudinalAction></PrivateAction></Private>"""
    return scenario(vehicle("Ego"), car + speed, parameters=PARAMETERS)


def test_parameters_derive_in_order_and_follow_values_set_from_outside() -> None:
    program = read_openscenario(parameter_scenario(), "p.xosc")
    assert program.parameters["_Speed"] == pytest.approx(10.0)
    program = read_openscenario(
        parameter_scenario(), "p.xosc", parameters={"Speed_kph": "72", "Lane": "-2"}
    )
    assert program.parameters["_Speed"] == pytest.approx(20.0)
    _world, run = start_world(parameter_scenario().replace('value="36"', 'value="54"'))
    ego = run.rt.entity("Ego")
    assert (ego.x, ego.y, ego.speed) == pytest.approx((80.0, -1.75, 15.0))


def test_a_value_that_breaks_its_constraints_is_an_error_at_its_line() -> None:
    with pytest.raises(ScenarioError) as raised:
        read_openscenario(parameter_scenario(), "p.xosc", parameters={"Lane": "-3"})
    assert raised.value.label == "p.xosc" and raised.value.line is not None
    assert "'Lane' = -3 breaks its constraints" in str(raised.value)
    with pytest.raises(ScenarioError, match="no parameter declared for Nope"):
        read_openscenario(parameter_scenario(), "p.xosc", parameters={"Nope": "1"})


CATALOG = """<?xml version="1.0"?><OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="1" date="2026-01-01T00:00:00" author="t" description="c"/>
  <Catalog name="cars">
    <Vehicle name="box" vehicleCategory="car">
      <ParameterDeclarations>
        <ParameterDeclaration name="length" parameterType="double" value="4"/>
      </ParameterDeclarations>
      <BoundingBox><Center x="1" y="0" z="0.7"/><Dimensions width="2" length="$length"
        height="1.4"/></BoundingBox>
      <Performance maxSpeed="20" maxAcceleration="3" maxDeceleration="8"/>
      <Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.6" trackWidth="1.6" positionX="3"
        positionZ="0.3"/>
        <RearAxle maxSteering="0" wheelDiameter="0.6" trackWidth="1.6" positionX="0"
          positionZ="0.3"/></Axles>
    </Vehicle>
  </Catalog></OpenSCENARIO>"""


def test_catalogue_entries_take_their_parameter_assignments() -> None:
    entities = """<ScenarioObject name="Truck"><CatalogReference catalogName="cars" entryName="box">
      <ParameterAssignments><ParameterAssignment parameterRef="length" value="${2 * 6}"/>
      </ParameterAssignments></CatalogReference></ScenarioObject>
      <ScenarioObject name="Car"><CatalogReference catalogName="cars" entryName="box"/>
        </ScenarioObject>"""
    program = read_openscenario(scenario(entities, ""), "c.xosc", [("cars.xosc", CATALOG)])
    lengths = {d.name: (d.length, d.max_speed) for d in program.entities}
    assert lengths == {"Truck": (12.0, 20.0), "Car": (4.0, 20.0)}
    with pytest.raises(ScenarioError, match="catalogue 'cars' has no entry 'bus'"):
        read_openscenario(
            scenario(entities.replace('"box"/>', '"bus"/>'), ""), "c.xosc", [("cars.xosc", CATALOG)]
        )


def test_the_ego_is_the_external_one_else_ego_or_hero_else_the_first_vehicle() -> None:
    def ego_of(entities: str) -> str | None:
        return read_openscenario(scenario(entities, ""), "e.xosc").ego

    assert ego_of(vehicle("A") + vehicle("hero")) == "hero"
    assert ego_of(vehicle("A") + vehicle("B")) == "A"
    external = vehicle("B").replace(
        "</Vehicle>",
        '</Vehicle><ObjectController><Controller name="ExternalController"/></ObjectController>',
    )
    assert ego_of(vehicle("Ego") + external) == "B"


def test_an_unsupported_element_is_one_line_naming_it_and_the_rest_still_runs() -> None:
    unsupported = """<GlobalAction><TrafficAction><TrafficSwarmAction semiMajorAxis="10"
      semiMinorAxis="5" innerRadius="2" offset="0" numberOfVehicles="3"><CentralObject
        entityRef="Ego"/>
      </TrafficSwarmAction></TrafficAction></GlobalAction>"""
    text = scenario(
        vehicle("Ego") + vehicle("Car"),
        teleport("Ego", lane(10)) + teleport("Car", lane(100)),
        story(
            "Car",
            event("Swarm", unsupported, start(time_is(0.5))),
            event(
                "Move",
                "<PrivateAction><TeleportAction><Position>"
                + lane(300)
                + "</Position></TeleportAction></PrivateAction>",
                start(time_is(0.5)),
                "parallel",
            ),
        ),
    )
    program = read_openscenario(text, "u.xosc")
    line = next(k for k, row in enumerate(text.splitlines(), 1) if "<TrafficAction>" in row)
    assert program.notes == (
        f"u.xosc:{line}: <TrafficAction> is not carried out by egosim; left out",
    )
    world, run = start_world(text)
    assert step(world, run, 1.0) == []  # reported once, when read
    assert run.rt.entity("Car").x == pytest.approx(300.0)


def test_the_monitors_and_trailers_of_1_3_are_one_line_each_and_the_car_still_runs() -> None:
    hitched = vehicle("Ego").replace(
        "</Axles>",
        '</Axles><TrailerHitch dx="-1"/><Trailer><EntityRef entityRef="Cart"/></Trailer>',
    )
    text = scenario(hitched, teleport("Ego", lane(10))).replace(
        "<CatalogLocations>",
        '<MonitorDeclarations><MonitorDeclaration name="m" value="true"/></MonitorDeclarations>'
        "<CatalogLocations>",
    )
    rows = text.splitlines()

    def line_of(tag: str) -> int:
        return next(k for k, row in enumerate(rows, 1) if f"<{tag}" in row)

    assert read_openscenario(text, "t.xosc").notes == (
        f"t.xosc:{line_of('MonitorDeclarations')}: <MonitorDeclarations> is not evaluated: "
        "egosim keeps no monitors",
        f"t.xosc:{line_of('TrailerHitch')}: <TrailerHitch> is not simulated: egosim's "
        "vehicles pull no trailers",
        f"t.xosc:{line_of('Trailer>')}: <Trailer> is not simulated: egosim's vehicles pull "
        "no trailers",
    )
    _, run = start_world(text)
    assert run.rt.entity("Ego").x == pytest.approx(10.0)


def test_mistakes_name_file_line_and_element() -> None:
    with pytest.raises(ScenarioError) as raised:
        read_openscenario(
            "<OpenSCENARIO>\n<FileHeader revMajor='1' revMinor='2'/>\n<Oops>", "bad.xosc"
        )
    assert raised.value.label == "bad.xosc" and raised.value.line == 3
    bad_speed = scenario(
        vehicle("Ego"), teleport("Ego", '<LanePosition roadId="1" laneId="-1" s="fast"/>')
    )
    with pytest.raises(ScenarioError) as raised:
        read_openscenario(bad_speed, "bad.xosc")
    assert "<LanePosition>: s: 'fast' is not a number" in str(raised.value)
    assert raised.value.line is not None


def test_a_position_that_cannot_be_placed_is_reported_when_it_runs() -> None:
    text = scenario(
        vehicle("Ego") + vehicle("Car"),
        teleport("Ego", lane(10)) + teleport("Car", lane(50, road="9")),
    )
    world, run = start_world(text)
    notes = run.rt.notes + step(world, run, 0.01)
    assert (
        any("no road '9' in the OpenDRIVE map" in n for n in notes)
        or not run.rt.entity("Car").placed
    )
    assert not math.isnan(run.rt.entity("Ego").x)
