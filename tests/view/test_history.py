"""The plots' history: a sample of every ego each 0.1 s of simulation time, the last
60 s of them kept, whatever the run's length."""

from __future__ import annotations

import pytest

from egosim.bridge import BridgeContext
from egosim.view.history import FIELDS, HISTORY_S, SPACING_S, PlotHistory
from egosim.view.snapshot import ego_entries
from egosim.world.vehicle import ControlCommand, Pose

DT = 0.01


def run(context: BridgeContext, history: PlotHistory, seconds: float) -> None:
    for _ in range(round(seconds / DT)):
        context.world.step(DT)
        history.record(context)


def only_ego(history: PlotHistory) -> dict:
    (ego,) = history.message()["egos"]
    return ego


def test_a_sample_every_tenth_of_a_second_as_the_frame_shows_the_ego(
    straight: BridgeContext,
) -> None:
    straight.world.egos[0].vehicle.command(ControlCommand(accel=0.5))
    history = PlotHistory()
    run(straight, history, 5.0)
    ego = only_ego(history)
    assert ego["id"] == straight.world.egos[0].unique_id
    times = ego["t"]
    assert len(times) == 50  # 0.01 s (the first tick), 0.11 s, ..., 4.91 s
    assert times[0] == pytest.approx(DT)
    assert list(times[1:] - times[:-1]) == pytest.approx([SPACING_S] * 49, abs=1e-9)
    # The last sample is the ego as the frame of that tick listed it.
    history_now = PlotHistory()
    history_now.record(straight)
    (entry,) = ego_entries(straight)
    latest = only_ego(history_now)
    assert {name: latest[name][0] for name in FIELDS} == pytest.approx(
        {name: entry[name] for name in FIELDS}
    )
    assert ego["speed"][-1] > ego["speed"][0] >= 0.0  # it drove off
    assert ego["accel_pedal"][-1] == pytest.approx(0.5)


def test_only_the_last_minute_is_kept(straight: BridgeContext) -> None:
    history = PlotHistory()
    run(straight, history, HISTORY_S + 10.0)
    times = only_ego(history)["t"]
    assert len(times) == round(HISTORY_S / SPACING_S) + 1
    assert times[-1] - times[0] == pytest.approx(HISTORY_S)
    assert times[-1] == pytest.approx(straight.world.sim_time, abs=SPACING_S)


def test_a_paused_world_adds_nothing(straight: BridgeContext) -> None:
    history = PlotHistory()
    run(straight, history, 1.0)
    kept = len(only_ego(history)["t"])
    straight.world.paused = True
    run(straight, history, 1.0)
    assert len(only_ego(history)["t"]) == kept


def test_egos_that_are_gone_are_forgotten(straight: BridgeContext) -> None:
    world = straight.world
    pose = world.ego_status(0).pose
    world.add_ego(world.egos[0].vehicle.model.name, Pose(x=pose.x + 20.0, y=pose.y, yaw=pose.yaw))
    history = PlotHistory()
    run(straight, history, 1.0)
    assert len(history.message()["egos"]) == 2
    world.keep_egos(1)
    run(straight, history, 0.2)
    assert [ego["id"] for ego in history.message()["egos"]] == [world.egos[0].unique_id]


def test_nothing_kept_yet_is_an_empty_message() -> None:
    message = PlotHistory().message()
    assert message == {"type": "history", "span_s": HISTORY_S, "spacing_s": SPACING_S, "egos": []}
