"""The embedded master's Master API and Parameter Server API, through MasterClient and through
the slave API callbacks it makes (publisherUpdate, paramUpdate, shutdown)."""

from __future__ import annotations

import contextlib
import threading
import time
from collections.abc import Iterator
from typing import Any
from xmlrpc.server import SimpleXMLRPCServer

import pytest

from egosim.ros1 import Master, MasterClient, MasterError, MasterUnreachableError
from egosim.ros1.errors import MulticallUnsupportedError
from egosim.ros1.node import MASTER_PROBE_TIMEOUT_S
from tests.conftest import free_port
from tests.ros1.helpers import PROFILE, STRING, string_bytes, string_text, wait_until

EVENT_SRV = PROFILE.service("morai_msgs/MoraiEventCmdSrv")


def test_registration_and_system_state(embedded_master):
    a = MasterClient(embedded_master.uri, "/a")
    b = MasterClient(embedded_master.uri, "/b")
    assert a.register_publisher("/t", "std_msgs/String", "http://a:1/") == []
    assert b.register_subscriber("/t", "std_msgs/String", "http://b:2/") == ["http://a:1/"]
    assert a.register_subscriber("/u", "*", "http://a:1/") == []
    b.register_service("/s", "rosrpc://b:3", "http://b:2/")
    assert a.lookup_node("/b") == "http://b:2/"
    assert a.lookup_service("/s") == "rosrpc://b:3"
    assert a.get_published_topics() == [("/t", "std_msgs/String")]
    assert dict(a.get_topic_types()) == {"/t": "std_msgs/String", "/u": "*"}
    publishers, subscribers, services = a.get_system_state()
    assert publishers == [["/t", ["/a"]]]
    assert sorted(map(tuple, [(t, tuple(n)) for t, n in subscribers])) == [
        ("/t", ("/b",)),
        ("/u", ("/a",)),
    ]
    assert services == [["/s", ["/b"]]]
    assert a.get_uri() == embedded_master.uri
    assert a.unregister_publisher("/t", "http://a:1/") == 1
    assert a.unregister_publisher("/t", "http://a:1/") == 0
    assert b.unregister_service("/s", "rosrpc://b:3") == 1
    with pytest.raises(MasterError):
        a.lookup_service("/s")


def test_relative_names_resolve_in_the_callers_namespace(embedded_master):
    client = MasterClient(embedded_master.uri, "/ns/node")
    client.register_publisher("rel", "std_msgs/String", "http://x:1/")
    client.set_param("~private", 1)
    client.set_param("relative", 2)
    assert client.get_published_topics() == [("/ns/rel", "std_msgs/String")]
    assert client.get_param("/ns/node/private") == 1
    assert client.get_param("/ns/relative") == 2


def test_parameter_tree(embedded_master):
    client = MasterClient(embedded_master.uri, "/n")
    client.set_param("/sim", {"map": {"name": "town", "size": 2}, "rate": 30})
    assert client.get_param("/sim/map") == {"name": "town", "size": 2}
    assert client.get_param("/sim/map/name") == "town"
    client.set_param("/sim/map", {"name": "city"})
    assert client.get_param("/sim") == {"map": {"name": "city"}, "rate": 30}
    assert client.has_param("/sim/map/name")
    assert not client.has_param("/sim/map/size")
    assert {"/sim/map/name", "/sim/rate"} <= set(client.get_param_names())
    client.delete_param("/sim/rate")
    with pytest.raises(KeyError):
        client.get_param("/sim/rate")
    with pytest.raises(MasterError):
        client.delete_param("/sim/rate")
    assert isinstance(client.get_param("/")["run_id"], str)


def test_search_param_goes_up_the_namespaces(embedded_master):
    client = MasterClient(embedded_master.uri, "/a/b/node")
    client.set_param("/a/rate", 10)
    client.set_param("/rate", 1)
    client.set_param("/a/b/map", {"name": "x"})
    assert client.search_param("rate") == "/a/rate"
    assert client.search_param("map/name") == "/a/b/map/name"
    assert client.search_param("missing") is None
    assert MasterClient(embedded_master.uri, "/other").search_param("rate") == "/rate"


def test_publisher_update_connects_and_disconnects_subscribers(embedded_master, make_node):
    listener = make_node("listener", master_uri=embedded_master.uri)
    received: list[str] = []
    sub = listener.subscribe("/chatter", STRING, lambda d, h: received.append(string_text(d)))
    talker = make_node("talker", master_uri=embedded_master.uri)
    pub = talker.advertise("/chatter", STRING)
    wait_until(lambda: sub.num_publishers == 1)
    pub.publish(string_bytes("one"))
    wait_until(lambda: received == ["one"])
    talker.shutdown()
    wait_until(lambda: sub.connections == [])
    # A publisher that comes back under the same name is connected to again.
    talker2 = make_node("talker", master_uri=embedded_master.uri)
    pub2 = talker2.advertise("/chatter", STRING)
    wait_until(lambda: pub2.num_subscribers == 1)
    pub2.publish(string_bytes("two"))
    wait_until(lambda: received == ["one", "two"])


def test_param_updates_reach_subscribers(embedded_master, make_node):
    node = make_node("watcher", master_uri=embedded_master.uri)
    other = MasterClient(embedded_master.uri, "/setter")
    updates: list[tuple[str, object]] = []
    got = threading.Condition()

    def on_update(key, value):
        with got:
            updates.append((key, value))
            got.notify_all()

    assert node.subscribe_param("/sim", on_update) == {}
    other.set_param("/sim/rate", 30)
    other.set_param("/sim", {"map": "town"})
    other.delete_param("/sim")
    expected = [("/sim/rate", 30), ("/sim", {"map": "town"}), ("/sim", {})]
    with got:
        assert got.wait_for(lambda: len(updates) >= 3, timeout=30)
    assert updates == expected


def test_second_node_with_same_name_shuts_down_the_first(embedded_master, make_node):
    first = make_node("sim", master_uri=embedded_master.uri)
    first.advertise("/a", STRING)
    reasons: list[str] = []
    first.on_shutdown(reasons.append)
    second = make_node("sim", master_uri=embedded_master.uri)
    second.advertise("/b", STRING)
    assert first.wait_for_shutdown(30)
    assert "new node registered with same name" in reasons[0]
    assert second.master.lookup_node("/sim") == second.uri


def test_node_starts_an_embedded_master_only_when_none_answers(make_node):
    uri = f"http://127.0.0.1:{free_port()}/"
    with pytest.raises(MasterUnreachableError):
        make_node("lonely", master_uri=uri, embedded_master="never")
    first = make_node("first", master_uri=uri)
    assert first.embedded_master is not None
    first.advertise("/x", STRING)
    second = make_node("second", master_uri=uri)
    assert second.embedded_master is None
    assert second.master.lookup_node("/first") == first.uri


def test_master_refuses_a_taken_port(embedded_master):
    with pytest.raises(OSError):
        Master(embedded_master.uri).start()


def test_shutdown_unregisters_everything_and_tells_the_owner(embedded_master, make_node):
    node = make_node("sim", master_uri=embedded_master.uri)
    node.advertise("/out", STRING)
    node.subscribe("/in", STRING, lambda data, header: None)
    node.advertise_service("/srv", EVENT_SRV, lambda request, header: b"")
    node.subscribe_param("/sim", lambda key, value: None)
    reasons: list[str] = []
    node.on_shutdown(reasons.append)
    observer = MasterClient(embedded_master.uri, "/observer")
    node.shutdown("simulation stopped")
    assert reasons == ["simulation stopped"]
    assert node.is_shutdown
    assert observer.get_system_state() == ([], [], [])
    with pytest.raises(MasterError):
        observer.lookup_node("/sim")


def test_a_held_lookup_waits_for_its_service_and_errs_once_the_hold_ends(embedded_master):
    stack = MasterClient(embedded_master.uri, "/stack")
    simulator = MasterClient(embedded_master.uri, "/simulator")
    embedded_master.hold_lookups(True)
    answers: dict[str, object] = {}

    def look(service: str) -> None:
        try:
            answers[service] = stack.lookup_service(service)
        except MasterError as error:
            answers[service] = error

    waiting = [threading.Thread(target=look, args=(s,)) for s in ("/provided", "/never")]
    for thread in waiting:
        thread.start()
    waiting[0].join(0.2)
    assert waiting[0].is_alive() and answers == {}  # nobody provides it yet
    simulator.register_service("/provided", "rosrpc://simulator:3", "http://simulator:2/")
    waiting[0].join(30)
    assert answers == {"/provided": "rosrpc://simulator:3"}
    assert waiting[1].is_alive()
    embedded_master.hold_lookups(False)
    waiting[1].join(30)
    assert isinstance(answers["/never"], MasterError)
    with pytest.raises(MasterError):  # no hold: at once
        stack.lookup_service("/never")


def _registered(master_uri: str) -> tuple[list[Any], list[Any], list[Any]]:
    return MasterClient(master_uri, "/observer").get_system_state()


def _registering_together_serves(master_uri: str, make_node) -> None:
    talker = make_node("talker", master_uri=master_uri)
    pub = talker.advertise("/chatter", STRING)
    node = make_node("grouped", master_uri=master_uri)
    received: list[str] = []
    with node.registering_together():
        node.advertise("/out", STRING)
        sub = node.subscribe("/chatter", STRING, lambda d, h: received.append(string_text(d)))
        node.advertise_service("/serve", EVENT_SRV, lambda data, header: data)
        publishers, subscribers, services = _registered(master_uri)
        assert ["/out", ["/grouped"]] not in publishers and services == []  # not yet
    publishers, subscribers, services = _registered(master_uri)
    assert ["/out", ["/grouped"]] in publishers
    assert ["/chatter", ["/grouped"]] in subscribers
    assert services == [["/serve", ["/grouped"]]]
    wait_until(lambda: sub.num_publishers == 1)  # the publishers its registration returned
    pub.publish(string_bytes("hello"))
    wait_until(lambda: received == ["hello"])
    node.shutdown()  # its unregistrations, together too
    publishers, subscribers, services = _registered(master_uri)
    assert services == [] and all("/grouped" not in nodes for _, nodes in publishers)
    assert all("/grouped" not in nodes for _, nodes in subscribers)


def test_registrations_made_together_reach_the_master_as_the_block_ends(embedded_master, make_node):
    _registering_together_serves(embedded_master.uri, make_node)


@contextlib.contextmanager
def serving(api: dict[str, Any], multicall: bool) -> Iterator[str]:
    """A master serving `api` (with or without system.multicall) on a thread; its URI."""
    server = SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False)
    for method, function in api.items():
        server.register_function(function, method)
    if multicall:
        server.register_multicall_functions()
    threading.Thread(target=server.serve_forever, daemon=True).start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/"
    finally:
        server.shutdown()
        server.server_close()


def test_a_node_that_needs_a_master_waits_for_a_slow_one(make_node):
    api = Master().api()
    answer_uri = api["getUri"]
    first_call = threading.Event()

    def slow_get_uri(*args: Any) -> Any:
        if not first_call.is_set():
            first_call.set()
            time.sleep(MASTER_PROBE_TIMEOUT_S + 0.5)
        return answer_uri(*args)

    with serving({**api, "getUri": slow_get_uri}, multicall=True) as uri:
        node = make_node("patient", master_uri=uri, embedded_master="never")
        assert node.embedded_master is None
        assert first_call.is_set()


def test_a_master_without_multicall_gets_them_one_by_one(make_node):
    with serving(Master().api(), multicall=False) as uri:
        with pytest.raises(MulticallUnsupportedError):
            MasterClient(uri, "/n").call_together([("getUri", ())])
        _registering_together_serves(uri, make_node)


@pytest.mark.parametrize("multicall", [True, False])
def test_a_registration_refused_in_a_group_raises_as_the_block_ends(make_node, multicall):
    def refuse(*args: Any) -> list[Any]:
        return [-1, "refused", 0]

    with serving({**Master().api(), "registerService": refuse}, multicall) as uri:
        node = make_node("grouped", master_uri=uri)
        with pytest.raises(MasterError, match="refused"), node.registering_together():
            node.advertise("/ok", STRING)
            node.advertise_service("/refused", EVENT_SRV, lambda data, header: data)
