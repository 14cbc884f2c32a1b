"""OpenSCENARIO texts for the tests, written from small parts, and worlds that run them
on the gallery's straight highway (lanes -1 and -2 east at y = -1.75 and -5.25, lanes 1
and 2 west at y = 1.75 and 5.25)."""

from __future__ import annotations

from functools import cache
from pathlib import Path

from egosim.maps import load_map
from egosim.scenario_files import openscenario_scenario
from egosim.world import World
from egosim.world.map import LaneMap
from egosim.world.openscenario import ScenarioRun, read_openscenario
from egosim.world.scenario import ScenarioLoadOptions

HIGHWAY = Path(__file__).parents[3] / "examples" / "openscenario" / "highway.xodr"
DT = 0.01


@cache
def highway() -> LaneMap:
    return load_map(str(HIGHWAY))


def vehicle(name: str, length: float = 4.0, width: float = 2.0, centre_x: float = 1.5) -> str:
    return f"""<ScenarioObject name="{name}"><Vehicle name="{name}_model" vehicleCategory="car">
      <BoundingBox><Center x="{centre_x}" y="0" z="0.7"/>
        <Dimensions width="{width}" length="{length}" height="1.4"/></BoundingBox>
      <Performance maxSpeed="70" maxAcceleration="10" maxDeceleration="10"/>
      <Axles><FrontAxle maxSteering="0.5" wheelDiameter="0.6" trackWidth="1.6" positionX="3"
        positionZ="0.3"/>
        <RearAxle maxSteering="0" wheelDiameter="0.6" trackWidth="1.6" positionX="0"
          positionZ="0.3"/></Axles>
    </Vehicle></ScenarioObject>"""


def pedestrian(name: str) -> str:
    return f"""<ScenarioObject name="{name}"><Pedestrian name="walker"
      pedestrianCategory="pedestrian" mass="70">
      <BoundingBox><Center x="0" y="0" z="0.9"/><Dimensions width="0.5" length="0.5"
        height="1.8"/></BoundingBox>
    </Pedestrian></ScenarioObject>"""


def teleport(entity: str, position: str) -> str:
    return f"""<Private entityRef="{entity}"><PrivateAction><TeleportAction><Position>{position}
      </Position></TeleportAction></PrivateAction></Private>"""


def speed_action(
    target: float, shape: str = "step", dimension: str = "time", value: float = 0
) -> str:
    return f"""<PrivateAction><LongitudinalAction><SpeedAction>
      <SpeedActionDynamics dynamicsShape="{shape}" value="{value}" dynamicsDimension="{dimension}"/>
      <SpeedActionTarget><AbsoluteTargetSpeed value="{target}"/></SpeedActionTarget>
    </SpeedAction></LongitudinalAction></PrivateAction>"""


def init_speed(entity: str, target: float) -> str:
    return f'<Private entityRef="{entity}">{speed_action(target)}</Private>'


def lane(s: float, lane_id: int = -1, offset: float = 0.0, road: str = "1") -> str:
    return f'<LanePosition roadId="{road}" laneId="{lane_id}" s="{s}" offset="{offset}"/>'


def time_is(value: float, rule: str = "greaterThan", edge: str = "none", delay: float = 0) -> str:
    return f"""<Condition name="t" delay="{delay}" conditionEdge="{edge}"><ByValueCondition>
      <SimulationTimeCondition value="{value}" rule="{rule}"/></ByValueCondition></Condition>"""


def start(*conditions: str) -> str:
    return f"<StartTrigger><ConditionGroup>{''.join(conditions)}</ConditionGroup></StartTrigger>"


def event(
    name: str, action: str, trigger: str = "", priority: str = "override", count: int = 1
) -> str:
    return f"""<Event name="{name}" priority="{priority}" maximumExecutionCount="{count}">
      <Action name="{name}Action">{action}</Action>{trigger}</Event>"""


def story(actor: str, *events: str, act_trigger: str = "", executions: int = 1) -> str:
    return f"""<Story name="S"><Act name="A"><ManeuverGroup name="G"
      maximumExecutionCount="{executions}">
      <Actors selectTriggeringEntities="false"><EntityRef entityRef="{actor}"/></Actors>
      <Maneuver name="M">{"".join(events)}</Maneuver></ManeuverGroup>{act_trigger}</Act></Story>"""


def set_variable(name: str, value: str) -> str:
    return f"""<GlobalAction><VariableAction variableRef="{name}"><SetAction value="{value}"/>
      </VariableAction></GlobalAction>"""


def scenario(
    entities: str,
    init: str,
    stories: str = "",
    stop: str = "",
    parameters: str = "",
    variables: str = "",
    minor: int = 3,
    catalogs: str = "",
    extra: str = "",
) -> str:
    stop_trigger = (
        f"<StopTrigger><ConditionGroup>{stop}</ConditionGroup></StopTrigger>" if stop else ""
    )
    return f"""<?xml version="1.0"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="{minor}" date="2026-01-01T00:00:00" author="test"
    description="test"/>
  <ParameterDeclarations>{parameters}</ParameterDeclarations>
  <VariableDeclarations>{variables}</VariableDeclarations>
  <CatalogLocations>{catalogs}</CatalogLocations>
  <RoadNetwork><LogicFile filepath="highway.xodr"/></RoadNetwork>
  <Entities>{entities}</Entities>
  <Storyboard><Init><Actions>{init}</Actions></Init>{stories}{stop_trigger}{extra}</Storyboard>
</OpenSCENARIO>"""


def start_world(
    text: str,
    drives_ego: bool = True,
    catalog_files: tuple[tuple[str, str], ...] = (),
    lane_map: LaneMap | None = None,
) -> tuple[World, ScenarioRun]:
    program = read_openscenario(text, "test.xosc", catalog_files)
    world = World(lane_map or highway())
    world.load_scenario(
        openscenario_scenario(program), ScenarioLoadOptions(scenario_drives_ego=drives_ego)
    )
    run = world.storyboard
    assert isinstance(run, ScenarioRun)
    return world, run


def step(world: World, run: ScenarioRun, seconds: float, drives_ego: bool = True) -> list[str]:
    """Step the storyboard and the world as the tick pipeline does; the notes."""
    notes = []
    for _ in range(round(seconds / DT)):
        notes += run.step(DT, drives_ego)
        world.step(DT)
    return notes
