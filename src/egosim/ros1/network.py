"""Where a node listens and how it names itself: ROS_MASTER_URI, ROS_IP, ROS_HOSTNAME."""

from __future__ import annotations

import ipaddress
import os
import socket
from collections.abc import Mapping
from dataclasses import dataclass
from urllib.parse import urlsplit

DEFAULT_MASTER_URI = "http://localhost:11311/"
LOOPBACK = "127.0.0.1"
#: Set to an address (0.0.0.0: every interface) to bind servers there instead of the
#: address the node advertises.
BIND_ENV = "EGOSIM_ROS_BIND"


def _address_of(host: str) -> str:
    """The IPv4 address a host name or address stands for (loopback if it resolves to none)."""
    try:
        return str(ipaddress.ip_address(host))
    except ValueError:
        try:
            return socket.gethostbyname(host)
        except OSError:
            return LOOPBACK


@dataclass(frozen=True)
class NetworkConfig:
    """``advertise_host`` goes into URIs given to peers; ``bind_host`` is what sockets bind."""

    master_uri: str
    advertise_host: str
    bind_host: str

    @classmethod
    def from_env(
        cls,
        env: Mapping[str, str] | None = None,
        master_uri: str | None = None,
        host: str | None = None,
        bind_host: str | None = None,
    ) -> NetworkConfig:
        """ROS_IP wins over ROS_HOSTNAME (as in rospy); with neither, everything stays on loopback.
        Servers listen on the address the node advertises (ROS_IP's, or ROS_HOSTNAME's as
        resolved), never on every interface unless asked: ``bind_host`` or EGOSIM_ROS_BIND."""
        env = os.environ if env is None else env
        uri = master_uri or env.get("ROS_MASTER_URI") or DEFAULT_MASTER_URI
        advertise = host or env.get("ROS_IP") or env.get("ROS_HOSTNAME") or LOOPBACK
        if bind_host is None:
            bind_host = env.get(BIND_ENV) or _address_of(advertise)
        return cls(master_uri=uri, advertise_host=advertise, bind_host=bind_host)


def master_bind_address(master_uri: str) -> tuple[str, int]:
    """The address an embedded master binds: the (IPv4) address of the URI's host and its port."""
    parts = urlsplit(master_uri)
    host = parts.hostname or "localhost"
    return socket.gethostbyname(host), 11311 if parts.port is None else parts.port


def http_uri(host: str, port: int) -> str:
    return f"http://{host}:{port}/"


def rosrpc_uri(host: str, port: int) -> str:
    return f"rosrpc://{host}:{port}"


def parse_rosrpc_uri(uri: str) -> tuple[str, int]:
    parts = urlsplit(uri)
    if parts.scheme != "rosrpc" or not parts.hostname or not parts.port:
        raise ValueError(f"not a rosrpc:// URI: {uri!r}")
    return parts.hostname, parts.port
