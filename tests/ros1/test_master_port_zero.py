"""A master asked for port 0 serves on a port the system picks, and says which."""

from __future__ import annotations

import xmlrpc.client
from urllib.parse import urlsplit

from egosim.ros1 import Master


def test_two_masters_on_port_zero_get_ports_of_their_own() -> None:
    first = Master("http://127.0.0.1:0/").start()
    second = Master("http://127.0.0.1:0/").start()
    try:
        ports = {urlsplit(m.uri).port for m in (first, second)}
        assert len(ports) == 2 and 0 not in ports and 11311 not in ports
        for master in (first, second):
            code, _, uri = xmlrpc.client.ServerProxy(master.uri).getUri("/probe")
            assert (code, uri) == (1, master.uri)
    finally:
        first.shutdown()
        second.shutdown()
