"""An ERP42 ego, as the WeGo ERP42 planner drives it: chosen in the scenario, capped at
its top speed whatever /ctrl_cmd asks, and described by VehicleSpec."""

from __future__ import annotations

import pytest

from egosim.bridge import HANDLERS, simulation_context
from egosim.bridge.context import BridgeContext
from egosim.bridge.scene.specs import serve_vehicle_spec
from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import parse_scenario

ERP42_SCENARIO = "map: straight\nego:\n  model: ERP42\n  start: {lane: R1_E_1, s: 10.0}\n"


def erp42_context() -> BridgeContext:
    world = World(build_builtin_map("straight"), parse_scenario(ERP42_SCENARIO))
    return simulation_context(world)


def test_a_55_kmh_ctrl_cmd_drives_the_erp42_at_its_25_kmh_cap() -> None:
    context = erp42_context()
    command = context.profile.message("morai_msgs/CtrlCmd").new(longlCmdType=2, velocity=55.0)
    handle, row = HANDLERS.subscribers["ctrl_cmd"].handle, context.row("ctrl_cmd")
    fastest = 0.0
    for _ in range(round(20.0 / context.world.physics_step_s)):
        handle(context, row, command)
        context.tick(context.world.physics_step_s)
        fastest = max(fastest, context.world.ego_status().speed)
    assert context.world.egos[0].vehicle.model.name == "ERP42"
    assert fastest * 3.6 <= 25.0 + 1e-9
    assert fastest * 3.6 == pytest.approx(25.0, abs=0.5)


def test_vehicle_spec_of_an_erp42_ego() -> None:
    context = erp42_context()
    profile = context.profile
    request = profile.message("morai_msgs/MoraiVehicleSpecSrvRequest").new(
        request=profile.message("morai_msgs/VehicleSpecIndex").new(
            unique_id=context.world.egos[0].unique_id
        )
    )
    spec = serve_vehicle_spec(context, context.row("vehicle_spec"), request).response
    assert (spec.size.x, spec.size.y) == pytest.approx((2.020, 1.160))
    assert spec.wheel_base == pytest.approx(1.040)
    assert spec.max_steering == pytest.approx(28.0)
