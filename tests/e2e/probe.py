"""A bare TCPROS subscriber handshake: what egosim answers a given md5sum with."""

from __future__ import annotations

import socket
import xmlrpc.client

from egosim.ros1.connection_header import read_header, write_header


def handshake(master_uri: str, topic: str, type_name: str, md5sum: str) -> dict[str, str]:
    """egosim's reply header to a subscriber of `topic` asking for `md5sum`."""
    _, _, node_uri = xmlrpc.client.ServerProxy(master_uri).lookupNode("/probe", "/egosim")
    _, _, (_, host, port) = xmlrpc.client.ServerProxy(node_uri).requestTopic(
        "/probe", topic, [["TCPROS"]]
    )
    with socket.create_connection((host, port), timeout=30) as sock:
        write_header(
            sock, {"callerid": "/probe", "topic": topic, "type": type_name, "md5sum": md5sum}
        )
        return read_header(sock, 1 << 20)
