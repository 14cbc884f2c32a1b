"""TCPROS services between egosim nodes and bare sockets: ok byte, errors, persistence, probe."""

from __future__ import annotations

import struct

import pytest

from egosim.ros1 import ConnectionRefusedByPeerError, ServiceError, ServiceType, TopicType
from tests.ros1.helpers import PROFILE, raw_connect, read_frame

EVENT_SRV = PROFILE.service("morai_msgs/MoraiEventCmdSrv")


def _gear_plus_one(request: bytes, header) -> bytes:
    event = EVENT_SRV.request.deserialize(request).request
    event.gear += 1
    return EVENT_SRV.response.serialize(EVENT_SRV.response.new(response=event))


def _request(gear: int) -> bytes:
    message = EVENT_SRV.request.new()
    message.request.gear = gear
    return EVENT_SRV.request.serialize(message)


@pytest.fixture
def server_node(embedded_master, make_node):
    node = make_node("sim", master_uri=embedded_master.uri)
    node.advertise_service("/event", EVENT_SRV, _gear_plus_one)
    return node


@pytest.mark.parametrize("persistent", [False, True])
def test_calls_return_the_handlers_response(server_node, make_node, persistent):
    client = make_node("client", master_uri=server_node.master_uri)
    proxy = client.service_proxy("/event", EVENT_SRV, persistent=persistent)
    for gear in (1, 2, 3):
        reply = EVENT_SRV.response.deserialize(proxy.call(_request(gear)))
        assert reply.response.gear == gear + 1
    assert server_node.services[0].requests == 3


def test_handler_exception_is_an_error_reply(embedded_master, make_node):
    node = make_node("sim", master_uri=embedded_master.uri)

    def broken(request, header):
        raise RuntimeError("no scenario loaded")

    node.advertise_service("/event", EVENT_SRV, broken)
    proxy = node.service_proxy("/event", EVENT_SRV, persistent=True)
    for _ in range(2):  # the persistent connection survives a failed call
        with pytest.raises(ServiceError, match="no scenario loaded"):
            proxy.call(_request(1))


def test_unknown_service_is_a_service_error(embedded_master, make_node):
    node = make_node("client", master_uri=embedded_master.uri)
    with pytest.raises(ServiceError, match="not available"):
        node.service_proxy("/missing", EVENT_SRV).call(b"")
    with pytest.raises(ServiceError):
        node.service_proxy("/missing", EVENT_SRV).wait_for_service(timeout=0.2)


def test_probe_gets_the_header_and_a_close(server_node):
    sock, header = raw_connect(
        server_node, {"callerid": "/rosservice", "service": "/event", "md5sum": "*", "probe": "1"}
    )
    with sock:
        assert header["type"] == EVENT_SRV.name
        assert header["md5sum"] == EVENT_SRV.md5sum
        assert header["request_type"] == EVENT_SRV.request.name
        assert header["response_type"] == EVENT_SRV.response.name
        assert sock.recv(1) == b""


def test_md5_mismatch_is_refused(server_node):
    sock, header = raw_connect(
        server_node, {"callerid": "/x", "service": "/event", "md5sum": "f" * 32}
    )
    with sock:
        assert "md5sums do not match" in header["error"]


def test_wire_format_of_ok_and_error_replies(embedded_master, make_node):
    node = make_node("sim", master_uri=embedded_master.uri)

    def handler(request, header):
        if request == b"fail":
            raise ValueError("bad request")
        return request.upper()

    node.advertise_service("/upper", EVENT_SRV, handler)
    fields = {"callerid": "/x", "service": "/upper", "md5sum": "*", "persistent": "1"}
    sock, _ = raw_connect(node, fields)
    with sock:
        sock.sendall(struct.pack("<I", 2) + b"ok")
        assert sock.recv(1) == b"\x01"
        assert read_frame(sock) == b"OK"
        sock.sendall(struct.pack("<I", 4) + b"fail")
        assert sock.recv(1) == b"\x00"
        assert read_frame(sock) == b"bad request"


def test_negotiation_serves_each_client_its_service_type(embedded_master, make_node):
    old = ServiceType(
        "demo/Cmd", "1" * 32, TopicType("demo/CmdRequest", "a"), TopicType("demo/CmdResponse", "b")
    )
    new = ServiceType(
        "demo/Cmd", "2" * 32, TopicType("demo/CmdRequest", "c"), TopicType("demo/CmdResponse", "d")
    )

    def negotiate(header):
        for variant in (old, new):
            if header["md5sum"] in (variant.md5sum, "*"):
                return variant
        raise ConnectionRefusedByPeerError(f"no release of demo/Cmd has md5 {header['md5sum']}")

    node = make_node("sim", master_uri=embedded_master.uri)
    node.advertise_service(
        "/cmd",
        new,
        lambda request, header: header["md5sum"].encode()[:1] + request,
        negotiate=negotiate,
    )
    assert node.service_proxy("/cmd", old).call(b"x") == b"1x"
    assert node.service_proxy("/cmd", new).call(b"y") == b"2y"
    _sock, header = raw_connect(node, {"callerid": "/x", "service": "/cmd", "md5sum": "3" * 32})
    _sock.close()
    assert header == {"error": f"no release of demo/Cmd has md5 {'3' * 32}"}
