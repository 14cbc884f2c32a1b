"""Routes at a fork (AssignRouteAction inline and from a route catalogue,
AcquirePositionAction), controllers that are not simulated, and catalogue entries of
every kind an entity, a maneuver group or an action takes."""

from __future__ import annotations

import pytest
from tests.world.openscenario.stories import (
    event,
    init_speed,
    pedestrian,
    scenario,
    speed_action,
    start,
    start_world,
    step,
    story,
    teleport,
    time_is,
    vehicle,
)
from tests.world.openscenario.test_signal_controllers import junction

from egosim.world.openscenario import read_openscenario
from egosim.world.scenario.errors import ScenarioError

# The test junction: road 4's lane 1 runs north up to the junction, where it forks onto
# road 2 (straight on, lane 2_0_-1), road 1 (right, east: 1_0_-1) and road 3 (left, west:
# 3_0_-1). The car starts 80 m before the junction at 10 m/s; the ego stands on road 3's
# lane towards the junction, out of its way.
APPROACH = '<LanePosition roadId="4" laneId="1" s="80"/>'
EAST = '<LanePosition roadId="1" laneId="-1" s="50"/>'
WEST = '<LanePosition roadId="3" laneId="-1" s="50"/>'


def waypoint(position: str) -> str:
    return f'<Waypoint routeStrategy="shortest"><Position>{position}</Position></Waypoint>'


def route(name: str, *positions: str) -> str:
    return f'<Route name="{name}" closed="false">{"".join(map(waypoint, positions))}</Route>'


def routing(action: str) -> str:
    return f'<Private entityRef="Car"><PrivateAction><RoutingAction>{action}</RoutingAction>\
</PrivateAction></Private>'


def at_the_fork(init: str = "", catalog_files: tuple[tuple[str, str], ...] = ()) -> str:
    """The lane the car drives on 12 s after it set off (about 40 m past the fork)."""
    text = scenario(
        vehicle("Ego") + vehicle("Car"),
        teleport("Ego", '<LanePosition roadId="3" laneId="1" s="90"/>')
        + teleport("Car", APPROACH)
        + init_speed("Car", 10.0)
        + init,
    ).replace('filepath="highway.xodr"', 'filepath="junction.xodr"')
    world, run = start_world(text, catalog_files=catalog_files, lane_map=junction())
    step(world, run, 12.0)
    car = run.rt.entity("Car")
    assert car.speed == pytest.approx(10.0)
    return run.rt.lane_map.lane_ids[car.lane]


ROUTES = f"""<?xml version="1.0"?><OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="3" date="2026-01-01T00:00:00" author="t" description="r"/>
  <Catalog name="routes">{route("left", APPROACH, WEST)}</Catalog></OpenSCENARIO>"""


def test_without_a_route_the_car_goes_straight_on() -> None:
    assert at_the_fork() == "2_0_-1"


def test_an_assigned_route_takes_its_exit_at_the_fork() -> None:
    assigned = routing(f"<AssignRouteAction>{route('right', APPROACH, EAST)}</AssignRouteAction>")
    assert at_the_fork(assigned) == "1_0_-1"


def test_a_route_from_a_catalogue_takes_its_exit() -> None:
    reference = routing(
        '<AssignRouteAction><CatalogReference catalogName="routes" entryName="left"/>'
        "</AssignRouteAction>"
    )
    assert at_the_fork(reference, (("routes.xosc", ROUTES),)) == "3_0_-1"


def test_acquiring_a_position_routes_the_car_to_it() -> None:
    acquire = routing(f"<AcquirePositionAction><Position>{EAST}</Position></AcquirePositionAction>")
    assert at_the_fork(acquire) == "1_0_-1"


def test_a_controller_that_is_not_external_is_reported_and_the_scenario_drives_on() -> None:
    assign = """<PrivateAction><ControllerAction><AssignControllerAction>
      <Controller name="ACC"><Properties><Property name="timeGap" value="1.5"/></Properties>
      </Controller></AssignControllerAction></ControllerAction></PrivateAction>"""
    activate = """<PrivateAction><ActivateControllerAction longitudinal="true"
      lateral="true"/></PrivateAction>"""
    text = scenario(
        vehicle("Ego") + vehicle("Car"),
        teleport("Ego", '<LanePosition roadId="1" laneId="-1" s="10"/>')
        + teleport("Car", '<LanePosition roadId="1" laneId="-1" s="100"/>')
        + init_speed("Car", 10.0),
        story(
            "Car",
            event("Assign", assign, start(time_is(0.5))),
            event("Activate", activate, start(time_is(1.0))),
            event("Faster", speed_action(15.0), start(time_is(1.5))),
        ),
    )
    line = next(k for k, row in enumerate(text.splitlines(), 1) if "<AssignController" in row)
    world, run = start_world(text)
    notes = step(world, run, 2.0)
    assert [n for n in notes if "controller" in n] == [
        f"test.xosc:{line}: <AssignControllerAction> on 'Car': the controller is not "
        "simulated; the default controller drives"
    ]
    # Both controller actions were done at once, so the events after them ran.
    assert run.rt.elements[("event", "Activate")].state == "completeState"
    assert run.rt.entity("Car").speed == pytest.approx(15.0)


CATALOGUE_KINDS = """<?xml version="1.0"?><OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="3" date="2026-01-01T00:00:00" author="t" description="c"/>
  <Catalog name="things">
    <Pedestrian name="child" pedestrianCategory="pedestrian" mass="30">
      <ParameterDeclarations>
        <ParameterDeclaration name="height" parameterType="double" value="1.2"/>
      </ParameterDeclarations>
      <BoundingBox><Center x="0" y="0" z="0.6"/><Dimensions width="0.4" length="0.3"
        height="$height"/></BoundingBox></Pedestrian>
    <MiscObject name="cone" miscObjectCategory="obstacle" mass="2">
      <BoundingBox><Center x="0" y="0" z="0.4"/><Dimensions width="0.4" length="0.4"
        height="0.8"/></BoundingBox></MiscObject>
    <Controller name="driver"><Properties>
      <Property name="esminiController" value="ExternalController"/></Properties></Controller>
    <Maneuver name="brake">
      <ParameterDeclarations>
        <ParameterDeclaration name="to" parameterType="double" value="0"/>
      </ParameterDeclarations>
      <Event name="Brake" priority="override"><Action name="BrakeAction"><PrivateAction>
        <LongitudinalAction><SpeedAction><SpeedActionDynamics dynamicsShape="step" value="0"
          dynamicsDimension="time"/><SpeedActionTarget><AbsoluteTargetSpeed value="$to"/>
        </SpeedActionTarget></SpeedAction></LongitudinalAction></PrivateAction></Action>
        <StartTrigger><ConditionGroup><Condition name="t" delay="0" conditionEdge="none">
          <ByValueCondition><SimulationTimeCondition value="1" rule="greaterThan"/>
          </ByValueCondition></Condition></ConditionGroup></StartTrigger></Event>
    </Maneuver>
    <Environment name="noon"><TimeOfDay animation="false" dateTime="2026-06-01T12:00:00"/>
      <Weather cloudState="free"/><RoadCondition frictionScaleFactor="1"/></Environment>
  </Catalog></OpenSCENARIO>"""


def test_entities_maneuvers_and_controllers_come_from_catalogues_with_assignments() -> None:
    def reference(entry: str, assignments: str = "") -> str:
        return f"""<CatalogReference catalogName="things" entryName="{entry}">
          <ParameterAssignments>{assignments}</ParameterAssignments></CatalogReference>"""

    driven = vehicle("Driven").replace(
        "</Vehicle>",
        f"</Vehicle><ObjectController>{reference('driver')}</ObjectController>",
    )
    entities = (
        vehicle("Ego")
        + driven
        + vehicle("Car")
        + f'<ScenarioObject name="Child">{reference("child", _assign("height", "1.1"))}'
        "</ScenarioObject>" + f'<ScenarioObject name="Cone">{reference("cone")}</ScenarioObject>'
    )
    group = f"""<Story name="S"><Act name="A"><ManeuverGroup name="G" maximumExecutionCount="1">
      <Actors selectTriggeringEntities="false"><EntityRef entityRef="Car"/></Actors>
      {reference("brake", _assign("to", "4"))}</ManeuverGroup></Act></Story>"""
    environment = f"""<GlobalAction><EnvironmentAction>{reference("noon")}</EnvironmentAction>
      </GlobalAction>"""
    text = scenario(
        entities,
        teleport("Driven", '<LanePosition roadId="1" laneId="-1" s="10"/>')
        + teleport("Car", '<LanePosition roadId="1" laneId="-1" s="100"/>')
        + init_speed("Car", 10.0)
        + teleport("Child", '<WorldPosition x="150" y="9" h="-1.57"/>')
        + teleport("Cone", '<WorldPosition x="200" y="7.5" h="0"/>')
        + environment,
        group,
    )
    files = (("things.xosc", CATALOGUE_KINDS),)
    program = read_openscenario(text, "test.xosc", files)
    # The catalogue's external controller makes "Driven" the ego (over the name "Ego").
    assert program.ego == "Driven"
    sizes = {d.name: (d.kind.name, d.length, d.width, d.height) for d in program.entities}
    assert sizes["Child"] == ("PEDESTRIAN", 0.3, 0.4, 1.1)
    assert sizes["Cone"] == ("MISC_OBJECT", 0.4, 0.4, 0.8)

    world, run = start_world(text, catalog_files=files)
    notes = step(world, run, 2.0)
    assert any("<EnvironmentAction> not applied" in note for note in notes)
    assert run.rt.entity("Car").speed == pytest.approx(4.0)  # the maneuver's assignment
    assert run.rt.entity("Child").in_world() and run.rt.entity("Cone").in_world()


def _assign(name: str, value: str) -> str:
    return f'<ParameterAssignment parameterRef="{name}" value="{value}"/>'


def test_an_unknown_catalogue_entry_is_an_error_naming_it() -> None:
    text = scenario(
        vehicle("Ego") + pedestrian("Walker"),
        teleport("Ego", '<LanePosition roadId="1" laneId="-1" s="10"/>'),
        """<Story name="S"><Act name="A"><ManeuverGroup name="G" maximumExecutionCount="1">
      <Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors>
      <CatalogReference catalogName="things" entryName="swerve"/></ManeuverGroup></Act>
      </Story>""",
    )
    with pytest.raises(ScenarioError, match="catalogue 'things' has no entry 'swerve'"):
        read_openscenario(text, "test.xosc", (("things.xosc", CATALOGUE_KINDS),))
