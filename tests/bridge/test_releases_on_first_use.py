"""The older morai_msgs releases' types are built when a peer of theirs first asks for
them: a simulator that only peers of its default release talk to never parses them, and
a peer of 24.r2 or 2021.08 is still recognised by its md5sum and served its release."""

from __future__ import annotations

import functools
import math
import time
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import Any

import pytest
from rosbags.interfaces.typing import Typesdict

from egosim.app.inbox import Inbox
from egosim.bridge import HANDLERS, Bridge, default_network_settings, simulation_context
from egosim.bridge.context import BridgeContext
from egosim.msgs import PROFILES, Profile, ServiceType
from egosim.msgs import profile as profile_module
from egosim.ros1 import Node
from egosim.world import World
from egosim.world.map import build_builtin_map
from tests.conftest import EVENT_TIMEOUT_S, free_port
from tests.contract import load_contract
from tests.e2e.probe import handshake

DEFAULT, *OLDER = PROFILES
EGO = ("/Ego_topic", "morai_msgs/EgoVehicleStatus")
CTRL = ("/ctrl_cmd", "morai_msgs/CtrlCmd")
SYNC_CMD = ("/SyncModeCmd", "morai_msgs/MoraiSyncModeCmdSrv")
WAIT_FOR_TICK = ("/SyncModeWaitForTick", "morai_msgs/MoraiWaitForTickSrv")
STEERING_RAD = 0.1


class CountedProfile(Profile):
    """A profile that notes each definition it parses."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.parsed: list[str] = []

    def _parse(self, store_name: str) -> Typesdict:
        self.parsed.append(store_name)
        return super()._parse(store_name)


@pytest.fixture
def served(monkeypatch: pytest.MonkeyPatch) -> Callable[[str], CountedProfile]:
    """The profiles `get_profile` gives for this test: fresh ones, counting their parses."""
    built = functools.cache(CountedProfile)
    monkeypatch.setattr(profile_module, "built_profile", built)
    return built


@dataclass
class Simulator:
    """A bridge with every default row bound on its own master, stepped by `run_until`."""

    node: Node
    context: BridgeContext
    inbox: Inbox

    def run_until(self, condition: Callable[[], bool], what: str) -> None:
        """Tick the world and run what its rows received until `condition` holds."""
        deadline = time.monotonic() + EVENT_TIMEOUT_S
        while not condition():
            assert time.monotonic() < deadline, f"{what} within {EVENT_TIMEOUT_S} s"
            self.context.tick(self.context.world.physics_step_s)
            self.inbox.drain()
            time.sleep(0.002)  # the peers' threads read what the tick sent

    def call(self, peer: Node, name: str, service: ServiceType[Any, Any], request: object) -> Any:
        """The response to `peer`'s `request` to the service `name`, run on this thread
        (the simulation loop's) as it arrives."""
        proxy = peer.service_proxy(name, service)
        with ThreadPoolExecutor(1) as pool:
            reply = pool.submit(proxy.call, service.request.serialize(request), EVENT_TIMEOUT_S)
            deadline = time.monotonic() + EVENT_TIMEOUT_S
            while not reply.done():
                assert time.monotonic() < deadline, f"{name} answers within {EVENT_TIMEOUT_S} s"
                self.inbox.wait(0.05)
        return service.response.deserialize(reply.result())


@pytest.fixture
def simulator(served: Callable[[str], CountedProfile]) -> Iterator[Simulator]:
    settings = default_network_settings()
    master = f"http://127.0.0.1:{free_port()}/"
    with Node("egosim", master_uri=master, rosout_logger=None, env={}) as node:
        inbox = Inbox()
        bridge = Bridge(node, settings, HANDLERS, inbox)
        context = simulation_context(
            World(build_builtin_map("straight")), settings=settings, bridge=bridge
        )
        bridge.open(context)
        yield Simulator(node, context, inbox)


@pytest.fixture
def peer(simulator: Simulator) -> Iterator[Node]:
    with Node("peer", master_uri=simulator.node.master_uri, rosout_logger=None, env={}) as node:
        yield node


def test_peers_of_the_default_release_leave_the_older_releases_unparsed(
    served: Callable[[str], CountedProfile], simulator: Simulator, peer: Node
) -> None:
    types = Profile(DEFAULT)
    received: list[bytes] = []
    peer.subscribe(EGO[0], types.message(EGO[1]), lambda data, _: received.append(data))
    simulator.run_until(lambda: len(received) > 1, "the default release's peer hears the ego")
    assert served(DEFAULT).parsed, "the default release is parsed for the rows it binds"
    assert {release: served(release).parsed for release in OLDER} == {r: [] for r in OLDER}


@pytest.mark.parametrize("release", OLDER)
def test_a_peer_of_an_older_release_is_served_it_and_parses_only_what_it_asks_for(
    served: Callable[[str], CountedProfile], simulator: Simulator, peer: Node, release: str
) -> None:
    """The peer names its types by the release's md5sums (the public contract's)."""
    contract = load_contract(release)
    types = Profile(release)  # the peer's own, not the simulator's
    ego, ctrl = types.message(EGO[1]), types.message(CTRL[1])
    assert ego.md5sum == contract["messages"][EGO[1]]["md5sum"]
    assert served(release).parsed == []

    received: list[Any] = []
    peer.subscribe(EGO[0], ego, lambda data, _: received.append(ego.deserialize(data)))
    command = ctrl.new(longlCmdType=2, velocity=10.0, steering=STEERING_RAD)
    steered_deg = math.degrees(STEERING_RAD)
    peer.advertise(CTRL[0], ctrl, latch=True).publish(ctrl.serialize(command))
    simulator.run_until(
        lambda: bool(received) and received[-1].wheel_angle == pytest.approx(steered_deg),
        f"the {release} peer's steering (rad) reaches its {release} ego status (deg)",
    )
    # a type is read in the first release of its md5sum (2021.08's CtrlCmd is 24.r2's)
    assert "morai_msgs/msg/EgoVehicleStatus" in served(release).parsed
    later = PROFILES[PROFILES.index(release) + 1 :]
    assert {r: served(r).parsed for r in later} == {r: [] for r in later}

    # WaitForTick differs in every release: the peer's is read in its own
    sync_cmd, wait_for_tick = types.service(SYNC_CMD[1]), types.service(WAIT_FOR_TICK[1])
    assert wait_for_tick.md5sum == contract["services"][WAIT_FOR_TICK[1]]["md5sum"]
    assert "morai_msgs/msg/MoraiWaitForTickSrvRequest" not in served(release).parsed
    start = types.message("morai_msgs/SyncModeCmd").new(user_id="peer", start_sync_mode=True)
    started = simulator.call(peer, SYNC_CMD[0], sync_cmd, sync_cmd.request.new(request=start))
    assert started.response.result
    frame = int(started.response.frame) + 1
    tick = types.message("morai_msgs/WaitForTick").new(user_id="peer", frame=frame)
    ticked = simulator.call(
        peer, WAIT_FOR_TICK[0], wait_for_tick, wait_for_tick.request.new(request=tick)
    )
    assert (ticked.response.tick_status, ticked.response.frame) == (True, frame)
    assert "morai_msgs/msg/MoraiWaitForTickSrvRequest" in served(release).parsed


def test_an_unknown_md5_is_refused_naming_every_release_and_its_md5(simulator: Simulator) -> None:
    reply = handshake(simulator.node.master_uri, EGO[0], EGO[1], "0123456789abcdef" * 2)
    for release in PROFILES:
        md5sum = load_contract(release)["messages"][EGO[1]]["md5sum"]
        assert f"{md5sum} ({release})" in reply["error"]
