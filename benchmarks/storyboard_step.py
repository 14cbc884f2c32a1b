"""What an OpenSCENARIO storyboard costs a tick: a 20-entity storyboard on the gallery's
highway (the ego in auto mode and 19 cars in four lanes, each with a speed change, a
lane change or a lane offset triggered by time, distance, headway, relative speed or
another element's state, and a stop trigger that never fires), stepped at 100 Hz.

Reported: the storyboard's step alone (decide, move, settle, hand over the poses) and
World.step on top of it (median and 95th percentile, us per tick), over --ticks ticks
after --warmup.

Usage: .venv/bin/python benchmarks/storyboard_step.py [--ticks 3000] [--warmup 300]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).parents[1]
sys.path.insert(0, str(ROOT))

from tests.world.openscenario.stories import (  # noqa: E402
    event,
    init_speed,
    lane,
    scenario,
    speed_action,
    start,
    teleport,
    time_is,
    vehicle,
)

from egosim.maps import load_map  # noqa: E402
from egosim.scenario_files import openscenario_scenario  # noqa: E402
from egosim.world import World  # noqa: E402
from egosim.world.openscenario import read_openscenario  # noqa: E402
from egosim.world.scenario import ScenarioLoadOptions  # noqa: E402

DT = 0.01
CARS = 19


def headway(car: str) -> str:
    return f"""<Condition name="h{car}" delay="0" conditionEdge="rising"><ByEntityCondition>
      <TriggeringEntities triggeringEntitiesRule="any"><EntityRef entityRef="{car}"/>
        </TriggeringEntities>
      <EntityCondition><TimeHeadwayCondition entityRef="Ego" value="1.5" freespace="true"
        rule="lessThan" coordinateSystem="entity"/></EntityCondition></ByEntityCondition>
          </Condition>"""


def lane_change(target: int) -> str:
    return f"""<PrivateAction><LateralAction><LaneChangeAction targetLaneOffset="0">
      <LaneChangeActionDynamics dynamicsShape="sinusoidal" value="4" dynamicsDimension="time"/>
      <LaneChangeTarget><AbsoluteTargetLane value="{target}"/></LaneChangeTarget>
    </LaneChangeAction></LateralAction></PrivateAction>"""


def benchmark_text() -> str:
    entities = vehicle("Ego")
    init = teleport("Ego", lane(20)) + init_speed("Ego", 25.0)
    stories = []
    for k in range(CARS):
        name = f"Car{k}"
        lane_id = (-1, -2, 1, 2)[k % 4]
        s = 60 + 40 * (k // 4) if lane_id < 0 else 900 - 40 * (k // 4)
        entities += vehicle(name)
        init += teleport(name, lane(s, lane_id)) + init_speed(name, 15.0 + k % 5)
        kind = k % 3
        if kind == 0:
            action, trigger = speed_action(30.0, "cubic", "time", 5.0), start(time_is(2.0 + k % 7))
        elif kind == 1:
            target = {-1: -2, -2: -1, 1: 2, 2: 1}[lane_id]
            action, trigger = lane_change(target), start(headway(name))
        else:
            action = """<PrivateAction><LateralAction><LaneOffsetAction continuous="false">
              <LaneOffsetActionDynamics maxLateralAcc="0.5" dynamicsShape="sinusoidal"/>
              <LaneOffsetTarget><AbsoluteTargetLaneOffset value="0.6"/></LaneOffsetTarget>
              </LaneOffsetAction></LateralAction></PrivateAction>"""
            trigger = start(time_is(5.0 + k % 4))
        stories.append(
            f"""<Story name="S{k}"><Act name="A{k}"><ManeuverGroup name="G{k}"
              maximumExecutionCount="1">
            <Actors selectTriggeringEntities="false"><EntityRef entityRef="{name}"/></Actors>
            <Maneuver name="M{k}">{event(f"E{k}", action, trigger)}</Maneuver></ManeuverGroup>
              </Act></Story>"""
        )
    return scenario(entities, init, "".join(stories), time_is(1e6))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ticks", type=int, default=3000)
    parser.add_argument("--warmup", type=int, default=300)
    args = parser.parse_args()
    lane_map = load_map(str(ROOT / "examples" / "openscenario" / "highway.xodr"))
    program = read_openscenario(benchmark_text(), "benchmark.xosc")
    world = World(lane_map)
    world.load_scenario(
        openscenario_scenario(program), ScenarioLoadOptions(scenario_drives_ego=True)
    )
    run = world.storyboard
    assert run is not None
    storyboard, whole = [], []
    for tick in range(args.warmup + args.ticks):
        t0 = time.perf_counter()
        run.step(DT, True)
        t1 = time.perf_counter()
        world.step(DT)
        t2 = time.perf_counter()
        if tick >= args.warmup:
            storyboard.append((t1 - t0) * 1e6)
            whole.append((t2 - t0) * 1e6)
    entities = len(run.rt.entities)  # type: ignore[attr-defined]

    def line(name: str, samples: list[float]) -> str:
        p95 = statistics.quantiles(samples, n=20)[-1]
        return f"{name:28s} median {statistics.median(samples):7.1f} us   p95 {p95:7.1f} us"

    print(f"{entities} entities, {args.ticks} ticks of {DT * 1000:.0f} ms")
    print(line("storyboard step", storyboard))
    print(line("storyboard + World.step", whole))


if __name__ == "__main__":
    main()
