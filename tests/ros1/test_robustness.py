"""Bad input from peers: malformed, truncated or oversized headers and frames, peers that
vanish, XML-RPC garbage. The node logs each once with the peer's address and keeps serving."""

from __future__ import annotations

import http.client
import logging
import os
import socket
import struct
import threading
import xmlrpc.client
from collections.abc import Callable
from typing import Any
from xmlrpc.server import SimpleXMLRPCServer

import pytest

from egosim.ros1 import BadRequestError, Limits, Node, ServiceError
from egosim.ros1.connection_header import encode_header, read_header
from egosim.ros1.tcpros_server import TcprosServer
from tests.conftest import EVENT_TIMEOUT_S
from tests.ros1.helpers import (
    PROFILE,
    STRING,
    ListenerOutOfDescriptors,
    drain,
    raw_subscribe,
    read_frame,
    send_raw,
    slave_call,
    string_bytes,
    string_text,
    uri_address,
    wait_until,
)


def _open_fds() -> int:
    return len(os.listdir("/proc/self/fd"))


def _warnings_naming(caplog: pytest.LogCaptureFixture, peer: str) -> list[str]:
    return [
        r.getMessage()
        for r in caplog.records
        if r.levelno >= logging.WARNING and peer in r.getMessage()
    ]


@pytest.mark.parametrize(
    ("name", "data"),
    [
        ("absurd header length", struct.pack("<I", 0xFFFFFFF0) + b"x" * 16),
        ("header length just over the limit", struct.pack("<I", 64 * 1024 + 1)),
        ("truncated header", struct.pack("<I", 100) + b"\x05\x00\x00\x00ab"),
        ("field overruns header", struct.pack("<I", 8) + struct.pack("<I", 99) + b"a=bc"),
        ("field without '='", encode_header({"x": "y"})[:4] + struct.pack("<I", 3) + b"xyz"),
        ("not even a length", b"\x01\x02"),
    ],
)
def test_bad_headers_are_logged_once_and_the_node_keeps_serving(
    embedded_master, make_node, caplog, name, data
):
    caplog.set_level(logging.WARNING, logger="egosim.ros1")
    node = make_node("pub", master_uri=embedded_master.uri)
    pub = node.advertise("/chatter", STRING, latch=True)
    pub.publish(string_bytes("still here"))
    with socket.create_connection(node.tcpros_address, timeout=EVENT_TIMEOUT_S) as sock:
        peer = "{}:{}".format(*sock.getsockname())
        sock.sendall(data)
        drain(sock)
    wait_until(lambda: _warnings_naming(caplog, peer))
    assert len(_warnings_naming(caplog, peer)) == 1, name
    sock, _header = raw_subscribe(node, "/chatter", STRING.md5sum)
    with sock:
        assert string_text(read_frame(sock)) == "still here"


def test_header_naming_neither_topic_nor_service_is_refused(embedded_master, make_node):
    node = make_node("pub", master_uri=embedded_master.uri)
    reply = send_raw(node.tcpros_address, encode_header({"callerid": "/x"}))
    assert b"error=connection header names neither a topic nor a service" in reply


def test_silent_peer_is_dropped_after_the_header_timeout(embedded_master, make_node):
    node = make_node("pub", master_uri=embedded_master.uri, limits=Limits(header_timeout=0.2))
    with socket.create_connection(node.tcpros_address, timeout=EVENT_TIMEOUT_S) as sock:
        assert sock.recv(1) == b""


def test_oversized_service_request_is_refused_and_service_keeps_serving(
    embedded_master, make_node, caplog
):
    caplog.set_level(logging.WARNING, logger="egosim.ros1")
    node = make_node("srv", master_uri=embedded_master.uri, limits=Limits(max_frame_bytes=1024))
    srv = PROFILE.service("morai_msgs/MoraiEventCmdSrv")
    node.advertise_service("/echo", srv, lambda request, header: request)
    fields = {"callerid": "/x", "service": "/echo", "md5sum": "*", "persistent": "1"}
    with socket.create_connection(node.tcpros_address, timeout=EVENT_TIMEOUT_S) as sock:
        peer = "{}:{}".format(*sock.getsockname())
        sock.sendall(encode_header(fields))
        read_header(sock, 1 << 16)
        sock.sendall(struct.pack("<I", 2048) + b"x" * 2048)
        assert drain(sock) == b""
    wait_until(lambda: _warnings_naming(caplog, peer))
    assert "exceeds the limit of 1024" in _warnings_naming(caplog, peer)[0]
    assert node.service_proxy("/echo", srv).call(b"small") == b"small"


class FakePublisher:
    """A slave API whose requestTopic points at a bare socket acting out ``behaviour``."""

    def __init__(self, behaviour: Callable[[socket.socket], None]) -> None:
        self._listener = socket.create_server(("127.0.0.1", 0))
        port = self._listener.getsockname()[1]
        self._rpc = SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False)
        self._rpc.register_function(
            lambda caller, topic, protocols: [1, "", ["TCPROS", "127.0.0.1", port]], "requestTopic"
        )
        self.uri = f"http://127.0.0.1:{self._rpc.server_address[1]}/"
        self.accepted = 0
        self._behaviour = behaviour
        threading.Thread(target=self._rpc.serve_forever, daemon=True).start()
        threading.Thread(target=self._accept, daemon=True).start()

    def _accept(self) -> None:
        while True:
            try:
                sock, _ = self._listener.accept()
            except OSError:
                return
            with sock:
                read_header(sock, 1 << 16)
                self.accepted += 1
                self._behaviour(sock)

    def close(self) -> None:
        self._rpc.shutdown()
        self._rpc.server_close()
        self._listener.close()


def _valid_header(sock: socket.socket) -> None:
    sock.sendall(encode_header({"callerid": "/fake", "md5sum": STRING.md5sum, "type": STRING.name}))


@pytest.mark.parametrize(
    ("name", "behaviour", "logged"),
    [
        (
            "absurd frame length",
            lambda s: (_valid_header(s), s.sendall(struct.pack("<I", 0xFFFFFFFF))),
            "exceeds the limit",
        ),
        (
            "vanishes mid-frame",
            lambda s: (_valid_header(s), s.sendall(struct.pack("<I", 100) + b"cut")),
            "after 3 of 100 bytes",
        ),
        (
            "garbage header",
            lambda s: s.sendall(struct.pack("<I", 5) + b"\x09\x00\x00\x00z"),
            "overruns",
        ),
        ("vanishes before its header", lambda s: None, "after 0 of 4 bytes"),
    ],
)
def test_subscriber_survives_broken_publishers(
    embedded_master, make_node, caplog, name, behaviour, logged
):
    caplog.set_level(logging.INFO, logger="egosim.ros1")
    node = make_node("sub", master_uri=embedded_master.uri)
    received: list[str] = []
    sub = node.subscribe("/chatter", STRING, lambda d, h: received.append(string_text(d)))
    fake = FakePublisher(behaviour)
    try:
        sub.update_publishers([fake.uri])
        wait_until(lambda: fake.accepted >= 2)  # it keeps trying, it did not die
        assert any(logged in r.getMessage() and fake.uri in r.getMessage() for r in caplog.records)
        talker = make_node("talker", master_uri=embedded_master.uri)
        pub = talker.advertise("/chatter", STRING)
        wait_until(lambda: pub.num_subscribers == 1)
        pub.publish(string_bytes("real"))
        wait_until(lambda: "real" in received)
    finally:
        fake.close()


def test_xmlrpc_garbage_gets_faults_and_servers_keep_answering(embedded_master, make_node):
    node = make_node("sim", master_uri=embedded_master.uri)
    for uri in (node.uri, embedded_master.uri):
        address = uri_address(uri)
        connection = http.client.HTTPConnection(*address, timeout=EVENT_TIMEOUT_S)
        connection.request(
            "POST", "/", body=b"<methodCall><oops", headers={"Content-Type": "text/xml"}
        )
        body = connection.getresponse().read()
        connection.close()
        assert b"<fault>" in body
        proxy = xmlrpc.client.ServerProxy(uri)
        with pytest.raises(xmlrpc.client.Fault):
            proxy.noSuchMethod("/x")
        with pytest.raises(xmlrpc.client.Fault):
            proxy.getPid()  # missing caller_id
        assert b"400" in send_raw(address, b"\x00\x01\x02 garbage\r\n\r\n")
        huge = b"POST / HTTP/1.0\r\nContent-Length: 1000000000000\r\n\r\n<methodCall>"
        assert b" 413 " in send_raw(address, huge)
        assert proxy.getPid("/x")[0] == 1


def test_no_threads_or_sockets_leak_after_bad_peers(embedded_master, make_node):
    node = make_node("sim", master_uri=embedded_master.uri)
    pub = node.advertise("/chatter", STRING)
    baseline_threads, baseline_fds = threading.active_count(), _open_fds()
    for _ in range(20):
        send_raw(node.tcpros_address, struct.pack("<I", 0xFFFFFFFF))
        send_raw(node.tcpros_address, encode_header({"topic": "/chatter"}))
        send_raw(
            node.tcpros_address,
            encode_header({"callerid": "/x", "topic": "/chatter", "md5sum": "bad"}),
        )
        sock, _ = raw_subscribe(node, "/chatter", "*")
        sock.close()  # a subscriber that vanishes
        assert slave_call(node, "getPid")[0] == 1
        for uri in (node.uri, embedded_master.uri):
            with pytest.raises(xmlrpc.client.Fault):
                xmlrpc.client.ServerProxy(uri).getPid()
    pub.publish(string_bytes("flush"))
    wait_until(lambda: pub.num_subscribers == 0)
    wait_until(lambda: threading.active_count() <= baseline_threads)
    wait_until(lambda: _open_fds() <= baseline_fds)


def test_registrations_naming_no_callable_api_are_refused_and_notices_keep_flowing(
    embedded_master, make_node
):
    master = xmlrpc.client.ServerProxy(embedded_master.uri, allow_none=True)
    for api in (None, "ftp://127.0.0.1/", 7):
        with pytest.raises(xmlrpc.client.Fault, match="caller_api"):
            master.registerPublisher("/evil", "/chatter", "std_msgs/String", api)
    with pytest.raises(xmlrpc.client.Fault, match="caller_api"):
        master.subscribeParam("/evil", "ftp://127.0.0.1/", "/cfg")
    # The master still tells a subscriber about a real publisher.
    _connected_chatter(embedded_master, make_node)


def test_a_parameter_xmlrpc_cannot_send_back_is_refused(embedded_master):
    master = xmlrpc.client.ServerProxy(embedded_master.uri)
    body = xmlrpc.client.dumps(("/x", "/cfg/big", 0), "setParam").replace(
        "<int>0</int>", f"<i8>{2**40}</i8>"
    )
    connection = http.client.HTTPConnection(*uri_address(embedded_master.uri), timeout=5)
    connection.request("POST", "/", body=body, headers={"Content-Type": "text/xml"})
    code, message, _ = xmlrpc.client.loads(connection.getresponse().read())[0][0]
    connection.close()
    assert code == -1 and "32-bit" in message
    assert master.setParam("/x", "/cfg/small", 2**31 - 1)[0] == 1
    assert master.getParam("/x", "/")[0] == 1


def test_a_method_response_posted_as_a_call_gets_a_fault_and_is_logged(embedded_master, caplog):
    caplog.set_level(logging.WARNING, logger="egosim.ros1")
    body = xmlrpc.client.dumps(([1, "ok", 0],), methodresponse=True)
    connection = http.client.HTTPConnection(*uri_address(embedded_master.uri), timeout=5)
    connection.request("POST", "/", body=body, headers={"Content-Type": "text/xml"})
    reply = connection.getresponse().read()
    connection.close()
    with pytest.raises(xmlrpc.client.Fault, match="methodResponse, not a methodCall"):
        xmlrpc.client.loads(reply)
    assert any("methodResponse" in r.getMessage() for r in caplog.records)
    assert xmlrpc.client.ServerProxy(embedded_master.uri).getPid("/x")[0] == 1


def test_a_malformed_publisher_update_changes_nothing(embedded_master, make_node):
    listener, talker, pub, received = _connected_chatter(embedded_master, make_node)
    reply = slave_call(listener, "publisherUpdate", "/chatter", talker.uri)  # not a list
    assert reply[0] == -1
    pub.publish(string_bytes("still here"))
    wait_until(lambda: "still here" in received)


class MalformedSlave:
    """A slave API whose requestTopic answers with `replies`, one per call, then the last."""

    def __init__(self, replies: list[object]) -> None:
        self._replies = replies
        self.calls = 0
        self._rpc = SimpleXMLRPCServer(("127.0.0.1", 0), logRequests=False, allow_none=True)
        self._rpc.register_function(self._request_topic, "requestTopic")
        self.uri = f"http://127.0.0.1:{self._rpc.server_address[1]}/"
        threading.Thread(target=self._rpc.serve_forever, daemon=True).start()

    def _request_topic(self, caller: str, topic: str, protocols: list) -> object:
        self.calls += 1
        return self._replies[min(self.calls, len(self._replies)) - 1]

    def close(self) -> None:
        self._rpc.shutdown()
        self._rpc.server_close()


@pytest.mark.parametrize(
    "reply",
    [[1, "ok"], [1, "", ["TCPROS", "127.0.0.1", "abc"]], [1, "", ["TCPROS", None, 5]], "x"],
)
def test_a_malformed_request_topic_reply_is_retried(embedded_master, make_node, reply):
    node = make_node("sub", master_uri=embedded_master.uri)
    sub = node.subscribe("/chatter", STRING, lambda d, h: None)
    slave = MalformedSlave([reply])
    try:
        sub.update_publishers([slave.uri])
        wait_until(lambda: slave.calls >= 2)  # the connection thread lives on and retries
    finally:
        slave.close()


def test_a_subscriber_that_sends_bytes_then_hangs_up_is_let_go(embedded_master, make_node):
    node = make_node("sim", master_uri=embedded_master.uri)
    pub = node.advertise("/quiet", STRING)
    baseline_threads = threading.active_count()
    for _ in range(10):
        sock, _ = raw_subscribe(node, "/quiet", "*")
        sock.sendall(b"x")  # a subscriber has nothing to say; this one does, then leaves
        sock.close()
    wait_until(lambda: pub.num_subscribers == 0)
    wait_until(lambda: threading.active_count() <= baseline_threads)


def _connected_chatter(embedded_master, make_node) -> tuple[Node, Node, Any, list[str]]:
    """A listener and a talker of /chatter, connected: (listener, talker, publisher, received)."""
    listener = make_node("listener", master_uri=embedded_master.uri)
    received: list[str] = []
    listener.subscribe("/chatter", STRING, lambda d, h: received.append(string_text(d)))
    talker = make_node("talker", master_uri=embedded_master.uri)
    pub = talker.advertise("/chatter", STRING)
    wait_until(lambda: pub.num_subscribers == 1)
    return listener, talker, pub, received


def test_the_tcpros_listener_outlives_running_out_of_descriptors(monkeypatch, caplog):
    create_server = socket.create_server
    listeners: list[ListenerOutOfDescriptors] = []

    def failing_server(*args: object, **kwargs: object) -> ListenerOutOfDescriptors:
        listeners.append(ListenerOutOfDescriptors(create_server(*args, **kwargs), 3))
        return listeners[-1]

    monkeypatch.setattr(socket, "create_server", failing_server)
    served: list[dict[str, str]] = []
    server = TcprosServer("127.0.0.1", lambda s, h, p: served.append(dict(h)) or False, Limits())
    try:
        with socket.create_connection(("127.0.0.1", server.port), timeout=5) as sock:
            sock.sendall(encode_header({"callerid": "/x", "topic": "/t"}))
            wait_until(lambda: served)
        assert listeners[0].failures == 0
        errors = [r for r in caplog.records if "accept failed" in r.getMessage()]
        assert len(errors) == 1  # once per episode, not once per retry
    finally:
        server.close()


def test_a_service_client_breaking_off_mid_request_is_logged(embedded_master, make_node, caplog):
    caplog.set_level(logging.WARNING, logger="egosim.ros1")
    node = make_node("srv", master_uri=embedded_master.uri)
    srv = PROFILE.service("morai_msgs/MoraiEventCmdSrv")
    node.advertise_service("/echo", srv, lambda request, header: request)
    fields = {"callerid": "/cut", "service": "/echo", "md5sum": "*", "persistent": "1"}
    with socket.create_connection(node.tcpros_address, timeout=EVENT_TIMEOUT_S) as sock:
        sock.sendall(encode_header(fields))
        read_header(sock, 1 << 16)
        sock.sendall(struct.pack("<I", 100) + b"half")
    wait_until(lambda: any("/cut" in r.getMessage() for r in caplog.records))
    assert "after 4 of 100 bytes" in next(
        r.getMessage() for r in caplog.records if "/cut" in r.getMessage()
    )
    with socket.create_connection(node.tcpros_address, timeout=EVENT_TIMEOUT_S) as sock:
        peer = "{}:{}".format(*sock.getsockname())
        sock.sendall(encode_header({"service": "/echo"}))  # no md5sum, no callerid
        assert "error" in read_header(sock, 1 << 16)
    wait_until(lambda: _warnings_naming(caplog, peer))
    assert node.service_proxy("/echo", srv).call(b"small") == b"small"


def test_an_xmlrpc_request_without_a_length_is_logged(embedded_master, caplog):
    caplog.set_level(logging.WARNING, logger="egosim.ros1")
    address = uri_address(embedded_master.uri)
    with socket.create_connection(address, timeout=EVENT_TIMEOUT_S) as sock:
        sock.sendall(
            b"POST / HTTP/1.0\r\nTransfer-Encoding: chunked\r\n\r\n5\r\nhello\r\n0\r\n\r\n"
        )
        assert b" 500 " in drain(sock)
    wait_until(lambda: any('" 500' in r.getMessage() for r in caplog.records))
    assert xmlrpc.client.ServerProxy(embedded_master.uri).getPid("/x")[0] == 1


def test_a_flood_of_refused_requests_is_one_line_with_a_count(embedded_master, make_node, caplog):
    caplog.set_level(logging.INFO, logger="egosim.ros1")
    node = make_node("srv", master_uri=embedded_master.uri)
    srv = PROFILE.service("morai_msgs/MoraiEventCmdSrv")

    def refuse(request: bytes, header: object) -> bytes:
        raise BadRequestError("undecodable request")

    node.advertise_service("/picky", srv, refuse)
    proxy = node.service_proxy("/picky", srv)
    for _ in range(300):
        with pytest.raises(ServiceError):
            proxy.call(b"\x00")
    lines = [r for r in caplog.records if "/picky" in r.getMessage()]
    assert len(lines) == 1
    assert "refused: undecodable request" in lines[0].getMessage()
    assert not lines[0].exc_info  # no traceback for a bad request
