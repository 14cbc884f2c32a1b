"""TCPROS topics between egosim nodes and bare sockets: header checks, latching, md5 `*`,
slow subscribers, the negotiation hook."""

from __future__ import annotations

import socket
from collections import Counter

from egosim.ros1 import ANY_TYPE, ConnectionRefusedByPeerError, TopicType
from egosim.ros1.connection_header import read_header, write_header
from tests.ros1.helpers import (
    STRING,
    raw_subscribe,
    read_frame,
    slave_call,
    string_bytes,
    string_text,
    wait_until,
)


def test_publisher_answers_with_its_header(embedded_master, make_node):
    node = make_node("pub", master_uri=embedded_master.uri)
    node.advertise("/chatter", STRING, latch=True)
    sock, header = raw_subscribe(node, "/chatter", STRING.md5sum, STRING.name)
    with sock:
        assert header["md5sum"] == STRING.md5sum
        assert header["type"] == "std_msgs/String"
        assert header["callerid"] == "/pub"
        assert header["latching"] == "1"
        assert header["message_definition"] == STRING.definition


def test_latched_message_goes_to_late_subscribers(embedded_master, make_node):
    node = make_node("pub", master_uri=embedded_master.uri)
    pub = node.advertise("/map", STRING, latch=True)
    pub.publish(string_bytes("first"))
    pub.publish(string_bytes("latest"))
    late = make_node("late", master_uri=embedded_master.uri)
    assert late_subscriber_gets(late, "/map") == ["latest"]


def test_a_message_latched_first_stays_latched_under_a_stream(embedded_master, make_node):
    node = make_node("pub", master_uri=embedded_master.uri)
    pub = node.advertise("/scene", STRING)
    pub.latch_first(string_bytes("map"))
    pub.publish(string_bytes("map"))
    for k in range(5):
        pub.publish(string_bytes(f"objects {k}"))
    sock, header = raw_subscribe(node, "/scene", STRING.md5sum, STRING.name)
    with sock:
        assert header["latching"] == "1"
        assert string_text(read_frame(sock)) == "map"
        wait_until(lambda: pub.num_subscribers == 1)
        pub.publish(string_bytes("objects 5"))
        assert string_text(read_frame(sock)) == "objects 5"


def late_subscriber_gets(listener, topic: str) -> list[str]:
    """What a subscriber joining now receives first: the latched message, if any."""
    received: list[str] = []
    listener.subscribe(topic, STRING, lambda data, header: received.append(string_text(data)))
    wait_until(lambda: received)
    return received


def test_md5_mismatch_gets_an_error_header(embedded_master, make_node):
    node = make_node("pub", master_uri=embedded_master.uri)
    pub = node.advertise("/chatter", STRING)
    sock, header = raw_subscribe(node, "/chatter", "0" * 32, "std_msgs/Other")
    with sock:
        assert set(header) == {"error"}
        assert STRING.md5sum in header["error"]
        assert "0" * 32 in header["error"]
        assert sock.recv(1) == b""
    assert pub.num_subscribers == 0


def test_unknown_topic_gets_an_error_header(embedded_master, make_node):
    node = make_node("pub", master_uri=embedded_master.uri)
    sock, header = raw_subscribe(node, "/nothing", "*")
    with sock:
        assert "not a publisher of [/nothing]" in header["error"]


def test_any_md5_subscriber_learns_the_type(embedded_master, make_node):
    node = make_node("pub", master_uri=embedded_master.uri)
    pub = node.advertise("/chatter", STRING)
    sock, header = raw_subscribe(node, "/chatter", "*")
    with sock:
        assert (header["md5sum"], header["type"]) == (STRING.md5sum, STRING.name)
        wait_until(lambda: pub.num_subscribers == 1)
        pub.publish(string_bytes("any"))
        assert string_text(read_frame(sock)) == "any"


def test_any_type_subscriber_gets_the_publishers_header(embedded_master, make_node):
    node = make_node("pub", master_uri=embedded_master.uri)
    pub = node.advertise("/chatter", STRING)
    received: list[tuple[bytes, dict]] = []
    node.subscribe("/chatter", ANY_TYPE, lambda data, header: received.append((data, header)))
    wait_until(lambda: pub.num_subscribers == 1)
    pub.publish(string_bytes("typed"))
    wait_until(lambda: received)
    data, header = received[0]
    assert string_text(data) == "typed"
    assert header["md5sum"] == STRING.md5sum


def test_tcp_nodelay_is_requested_and_honoured(embedded_master, make_node):
    node = make_node("pub", master_uri=embedded_master.uri)
    pub = node.advertise("/chatter", STRING)
    received: list[str] = []
    node.subscribe(
        "/chatter", STRING, lambda d, h: received.append(string_text(d)), tcp_nodelay=True
    )
    wait_until(lambda: pub.num_subscribers == 1)
    outbox = pub._outboxes[0]
    assert outbox.sock.getsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY)
    pub.publish(string_bytes("fast"))
    wait_until(lambda: received == ["fast"])


def test_stalled_subscriber_blocks_neither_publish_nor_others(embedded_master, make_node):
    node = make_node("pub", master_uri=embedded_master.uri)
    pub = node.advertise("/points", STRING, queue_size=5)
    stalled = socket.socket()
    stalled.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    stalled.connect(node.tcpros_address)
    write_header(stalled, {"callerid": "/stalled", "topic": "/points", "md5sum": "*"})
    read_header(stalled, 1 << 16)
    listener = make_node("listener", master_uri=embedded_master.uri)
    received: list[str] = []
    listener.subscribe("/points", STRING, lambda d, h: received.append(string_text(d)))
    wait_until(lambda: pub.num_subscribers == 2)
    padding = "x" * 20_000
    count = 500  # 10 MB: far more than the stalled socket's buffers hold
    for i in range(count):
        pub.publish(string_bytes(f"{i} {padding}"))
    wait_until(lambda: received and received[-1].startswith(f"{count - 1} "))
    publish_stats = slave_call(node, "getBusStats")[2][0]
    (topic, published, connections) = publish_stats[0]
    assert (topic, published) == ("/points", count)
    info = {c[1]: c for c in slave_call(node, "getBusInfo")[2]}
    stalled_id = info["/stalled"][0]
    dropped = {conn[0]: conn[4] for conn in connections}
    assert dropped[stalled_id] > 0
    stalled.close()


def test_negotiation_serves_each_subscriber_its_variant(embedded_master, make_node):
    old = TopicType("demo/Status", "1" * 32, "int32 a\n")
    new = TopicType("demo/Status", "2" * 32, "int32 a\nint32 b\n")

    def negotiate(header):
        wanted = header["md5sum"]
        for variant in (old, new):
            if wanted == variant.md5sum:
                return variant
        if wanted == "*":
            return new
        raise ConnectionRefusedByPeerError(f"no release of demo/Status has md5 {wanted}")

    node = make_node("pub", master_uri=embedded_master.uri)
    pub = node.advertise("/status", new, negotiate=negotiate, latch=True)
    calls: Counter[str] = Counter()

    def serialize(md5: str) -> bytes:
        calls[md5] += 1
        return md5[:1].encode() * 3

    sock_old, header_old = raw_subscribe(node, "/status", old.md5sum, callerid="/a")
    sock_old2, _ = raw_subscribe(node, "/status", old.md5sum, callerid="/b")
    sock_new, header_new = raw_subscribe(node, "/status", new.md5sum, callerid="/c")
    sock_bad, header_bad = raw_subscribe(node, "/status", "3" * 32, callerid="/d")
    assert (header_old["md5sum"], header_old["message_definition"]) == (old.md5sum, old.definition)
    assert header_new["md5sum"] == new.md5sum
    assert header_bad == {"error": f"no release of demo/Status has md5 {'3' * 32}"}
    wait_until(lambda: pub.num_subscribers == 3)
    pub.publish_variants(serialize)
    assert calls == {old.md5sum: 1, new.md5sum: 1}
    assert [read_frame(s) for s in (sock_old, sock_old2, sock_new)] == [b"111", b"111", b"222"]
    pub.publish_variants({old.md5sum: b"o", new.md5sum: b"n"})
    assert [read_frame(s) for s in (sock_old, sock_old2, sock_new)] == [b"o", b"o", b"n"]
    # A late subscriber gets the latched message in its own variant.
    sock_late, _ = raw_subscribe(node, "/status", old.md5sum, callerid="/e")
    assert read_frame(sock_late) == b"o"
    for sock in (sock_old, sock_old2, sock_new, sock_bad, sock_late):
        sock.close()


def test_a_burst_arrives_whole_in_order_and_latches_its_last(embedded_master, make_node):
    node = make_node("pub", master_uri=embedded_master.uri)
    pub = node.advertise("/status", STRING, latch=True)
    sock, _ = raw_subscribe(node, "/status", STRING.md5sum, STRING.name)
    with sock:
        wait_until(lambda: pub.num_subscribers == 1)
        burst = [f"intersection {k}" for k in range(32)]
        pub.publish_many([string_bytes(text) for text in burst])
        assert [string_text(read_frame(sock)) for _ in burst] == burst
    assert pub.messages_published == len(burst)
    late = make_node("late", master_uri=embedded_master.uri)
    assert late_subscriber_gets(late, "/status") == ["intersection 31"]


def test_a_subscriber_that_has_the_reply_gets_every_later_message(embedded_master, make_node):
    # A stack publishing the moment it is connected (a burst larger than the queue) loses
    # nothing: the reply header is the subscriber's signal that it is connected.
    node = make_node("pub", master_uri=embedded_master.uri)
    pub = node.advertise("/burst", STRING, queue_size=4)
    for attempt in range(20):
        sock, _ = raw_subscribe(node, "/burst", STRING.md5sum, STRING.name)
        with sock:
            pub.publish_many([string_bytes(f"{attempt}/{k}") for k in range(3)])
            pub.publish(string_bytes(f"{attempt}/3"))
            assert [string_text(read_frame(sock)) for _ in range(4)] == [
                f"{attempt}/{k}" for k in range(4)
            ], f"attempt {attempt}"


def test_output_held_in_a_block_arrives_whole_and_in_order_after_it(embedded_master, make_node):
    node = make_node("pub", master_uri=embedded_master.uri)
    pub = node.advertise("/clock_like", STRING)
    other = node.advertise("/status_like", STRING)
    clock_sock, _ = raw_subscribe(node, "/clock_like", STRING.md5sum, STRING.name)
    status_sock, _ = raw_subscribe(node, "/status_like", STRING.md5sum, STRING.name)
    with clock_sock, status_sock:
        wait_until(lambda: pub.num_subscribers == 1 and other.num_subscribers == 1)
        with node.holding_output():
            for frame in range(200):
                pub.publish(string_bytes(f"frame {frame}"))
                if frame % 10 == 0:
                    other.publish_many([string_bytes(f"{frame}/{k}") for k in range(32)])
        assert [string_text(read_frame(clock_sock)) for _ in range(200)] == [
            f"frame {frame}" for frame in range(200)
        ]
        assert [string_text(read_frame(status_sock)) for _ in range(20 * 32)] == [
            f"{frame}/{k}" for frame in range(0, 200, 10) for k in range(32)
        ]
        # Released: later messages go out on their own again.
        pub.publish(string_bytes("after"))
        assert string_text(read_frame(clock_sock)) == "after"


def test_held_output_keeps_its_order_around_large_messages(embedded_master, make_node):
    # Small messages kept during a hold go out before a large one published after them,
    # and what follows the large one after it, with the hold ended or not.
    node = make_node("pub", master_uri=embedded_master.uri)
    pub = node.advertise("/cloud_like", STRING)
    sock, _ = raw_subscribe(node, "/cloud_like", STRING.md5sum, STRING.name)
    with sock:
        wait_until(lambda: pub.num_subscribers == 1)
        texts = ["small 0", "x" * 100_000, "small 1", "small 2", "y" * 70_000, "small 3"]
        with node.holding_output():
            for text in texts:
                pub.publish(string_bytes(text))
        pub.publish(string_bytes("after"))
        assert [string_text(read_frame(sock)) for _ in range(len(texts) + 1)] == [
            *texts,
            "after",
        ]
