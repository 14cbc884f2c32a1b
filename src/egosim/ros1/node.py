"""A ROS 1 node: name, master connection, slave API server, TCPROS server, and the topics,
services and parameter subscriptions it owns."""

from __future__ import annotations

import contextlib
import itertools
import logging
import os
import socket
import threading
import time
from collections.abc import Callable, Iterator, Mapping
from typing import Any, Literal, NamedTuple

from .connection_header import error_header, write_header
from .errors import MasterError, MasterUnreachableError, MulticallUnsupportedError, Ros1Error
from .master import Master
from .master_client import MasterClient
from .master_watch import MasterWatch
from .names import NameResolver, canonicalize, join, parse_argv, validate_name
from .network import NetworkConfig, http_uri, rosrpc_uri
from .publication import Negotiator, OutputHold, Publisher
from .rosout import ROSOUT_TOPIC, RosoutHandler, log_type
from .rpc import XmlRpcServer
from .service import ServiceHandler, ServiceNegotiator, ServiceProxy, ServiceServer
from .slave_api import SlaveApi
from .subscription import MessageCallback, Subscriber
from .tcpros import Limits
from .tcpros_server import TcprosServer
from .types import MessageTypeInfo, ServiceTypeInfo

log = logging.getLogger(__name__)

EmbeddedMaster = Literal["auto", "never", "always"]
ParamCallback = Callable[[str, Any], None]
_MISSING: Any = object()
#: Time budget for unregistering everything from the master when shutting down (s).
SHUTDOWN_BUDGET_S = 1.0
#: How long to wait for an existing master to answer before starting an embedded one (s). A
#: node that never starts one waits the client's full timeout: a loaded master is slow, not gone.
MASTER_PROBE_TIMEOUT_S = 1.0


class _Call(NamedTuple):
    """A Master API call kept for a request of several (Node.registering_together), and
    what takes its value."""

    method: str
    args: tuple[Any, ...]
    then: Callable[[Any], None] | None = None


class Node:
    """A ROS 1 node.

    ``argv`` may carry ``__name:=``, ``__ns:=``, ``__master:=``, ``__ip:=``, ``__hostname:=``,
    ``_param:=value`` and ``from:=to`` remappings. ``embedded_master``: ``"auto"`` starts a
    master at ROS_MASTER_URI when nothing answers there, ``"always"`` insists on starting
    one, ``"never"`` requires an existing one. Log records of ``rosout_logger`` (INFO and
    above) are published on /rosout; ``None`` disables /rosout.
    """

    def __init__(
        self,
        name: str,
        argv: list[str] | None = None,
        *,
        namespace: str | None = None,
        master_uri: str | None = None,
        host: str | None = None,
        bind_host: str | None = None,
        embedded_master: EmbeddedMaster = "auto",
        limits: Limits | None = None,
        rosout_logger: str | None = "egosim",
        env: Mapping[str, str] | None = None,
    ) -> None:
        env = os.environ if env is None else env
        args = parse_argv(list(argv or []))
        base = validate_name(args.name or name)
        namespace = args.namespace or namespace or env.get("ROS_NAMESPACE") or "/"
        self.name = canonicalize(base) if base.startswith("/") else join(namespace, base)
        self.resolver = NameResolver(self.name, args.remappings)
        self.limits = limits or Limits()
        self.network = NetworkConfig.from_env(
            env,
            master_uri=args.special.get("__master") or master_uri,
            host=args.special.get("__ip") or args.special.get("__hostname") or host,
            bind_host=bind_host,
        )
        self.master = MasterClient(self.network.master_uri, self.name, self.limits.connect_timeout)
        self.embedded_master = self._join_or_start_master(embedded_master)

        self._lock = threading.RLock()
        self._together = threading.local()
        """The calls of a registering_together block (calls: list of _Call), per thread."""
        self._output_hold = OutputHold()
        self._publishers: dict[str, Publisher] = {}
        self._subscribers: dict[str, Subscriber] = {}
        self._services: dict[str, ServiceServer] = {}
        self._proxies: list[ServiceProxy] = []
        self._param_callbacks: dict[str, list[ParamCallback]] = {}
        # What this node set on the parameter server, to set again on a new master.
        self._params_set: dict[str, Any] = {}
        self._shutdown_callbacks: list[Callable[[str], None]] = []
        self._shutdown_request_handler: Callable[[str], None] | None = None
        self._connection_ids = itertools.count(1)
        self._shutdown_started = False
        self._shutdown_deadline = 0.0
        self._stopped = threading.Event()
        self.shutdown_reason = ""

        self._rosout_handler: RosoutHandler | None = None
        self._rosout_logger = rosout_logger
        self._tcpros = TcprosServer(self.network.bind_host, self._dispatch, self.limits)
        self._slave = XmlRpcServer((self.network.bind_host, 0), name=f"slave api {self.name}")
        self._slave.register_api(SlaveApi(self).functions())
        self._slave.start()
        self.uri = http_uri(self.network.advertise_host, self._slave.port)
        try:
            for key, value in args.private_params.items():
                self.set_param("~" + key, value)
            if rosout_logger is not None:
                rosout = self.advertise(ROSOUT_TOPIC, log_type(), latch=True)
                self._rosout_handler = RosoutHandler(rosout, self.name)
                logging.getLogger(rosout_logger).addHandler(self._rosout_handler)
        except BaseException:
            self.shutdown("start-up failed")
            raise
        if self.embedded_master is None:
            MasterWatch(self.master, self.reregister, self._stopped).start()
        log.info("node %s up at %s, master %s", self.name, self.uri, self.master_uri)

    # --- master -----------------------------------------------------------------------------
    def _join_or_start_master(self, mode: EmbeddedMaster) -> Master | None:
        if mode != "always":
            try:
                self.master.get_uri(timeout=MASTER_PROBE_TIMEOUT_S if mode == "auto" else None)
                return None
            except MasterUnreachableError:
                if mode == "never":
                    raise
        try:
            master = Master(self.network.master_uri).start()
        except OSError:
            if mode == "always":
                raise
            # Another process started a master at the same address first: join it.
            self.master.get_uri()
            return None
        self.master.master_uri = master.uri
        return master

    @property
    def master_uri(self) -> str:
        return self.master.master_uri

    @property
    def tcpros_address(self) -> tuple[str, int]:
        return self.network.advertise_host, self._tcpros.port

    def resolve_name(self, name: str) -> str:
        """Resolve a global, relative or private (``~``) name and apply remappings."""
        return self.resolver.resolve(name)

    def _next_connection_id(self) -> int:
        return next(self._connection_ids)

    # --- topics -----------------------------------------------------------------------------
    def advertise(
        self,
        topic: str,
        msg_type: MessageTypeInfo,
        *,
        latch: bool = False,
        queue_size: int = 100,
        negotiate: Negotiator | None = None,
    ) -> Publisher:
        """Publish ``topic``. ``negotiate`` (optional) picks the type served on each
        connection from the subscriber's header; the master is told ``msg_type``."""
        name = self.resolve_name(topic)
        publisher = Publisher(
            name,
            msg_type,
            self.name,
            latch=latch,
            queue_size=queue_size,
            negotiate=negotiate,
            on_close=self._release_publisher,
            output_hold=self._output_hold,
        )
        with self._lock:
            self._check_running()
            if name in self._publishers:
                raise Ros1Error(f"{self.name} already publishes {name}")
            self._publishers[name] = publisher
        self._register("registerPublisher", (name, msg_type.name, self.uri))
        return publisher

    def subscribe(
        self,
        topic: str,
        msg_type: MessageTypeInfo,
        callback: MessageCallback,
        *,
        tcp_nodelay: bool = False,
    ) -> Subscriber:
        """Subscribe to ``topic``; ``callback(data, publisher_header)`` runs on the thread of
        the publisher's connection. ``msg_type`` with md5sum ``*`` accepts any type."""
        name = self.resolve_name(topic)
        subscriber = Subscriber(
            name,
            msg_type,
            self.name,
            callback,
            limits=self.limits,
            tcp_nodelay=tcp_nodelay,
            next_connection_id=self._next_connection_id,
            on_close=self._release_subscriber,
        )
        with self._lock:
            self._check_running()
            if name in self._subscribers:
                raise Ros1Error(f"{self.name} already subscribes to {name}")
            self._subscribers[name] = subscriber
        self._register(
            "registerSubscriber",
            (name, msg_type.name, self.uri),
            lambda uris: subscriber.update_publishers(list(uris)),
        )
        return subscriber

    @contextlib.contextmanager
    def holding_output(self) -> Iterator[None]:
        """Topic data written inside the block is kept by each connection and written 64
        KiB at a time, the rest when the block ends (a message that large goes out as it
        comes, after what was kept): a burst of small messages then costs one system call
        and wakes each subscriber once instead of once per message. Subscribers get the
        block's messages, in order, by the time it has ended."""
        self._output_hold.begin()
        try:
            yield
        finally:
            self._output_hold.end()

    @property
    def publishers(self) -> list[Publisher]:
        with self._lock:
            return list(self._publishers.values())

    @property
    def subscribers(self) -> list[Subscriber]:
        with self._lock:
            return list(self._subscribers.values())

    def publisher(self, topic: str) -> Publisher | None:
        with self._lock:
            return self._publishers.get(topic)

    def publishers_updated(self, topic: str, publisher_uris: list[str]) -> None:
        with self._lock:
            subscriber = self._subscribers.get(topic)
        if subscriber is not None:
            subscriber.update_publishers(publisher_uris)

    # --- services ---------------------------------------------------------------------------
    def advertise_service(
        self,
        service: str,
        srv_type: ServiceTypeInfo,
        handler: ServiceHandler,
        *,
        negotiate: ServiceNegotiator | None = None,
    ) -> ServiceServer:
        """Provide ``service``; ``handler(request_bytes, client_header) -> response_bytes``
        runs on the client's connection thread. ``negotiate`` (optional) picks the type
        served on each connection from the client's header; the master is told nothing of
        types (services register by name)."""
        name = self.resolve_name(service)
        server = ServiceServer(
            name,
            srv_type,
            self.name,
            handler,
            limits=self.limits,
            on_close=self._release_service,
            negotiate=negotiate,
        )
        with self._lock:
            self._check_running()
            if name in self._services:
                raise Ros1Error(f"{self.name} already provides {name}")
            self._services[name] = server
        self._register("registerService", (name, self._service_uri, self.uri))
        return server

    @property
    def services(self) -> list[ServiceServer]:
        with self._lock:
            return list(self._services.values())

    @property
    def _service_uri(self) -> str:
        return rosrpc_uri(*self.tcpros_address)

    def service_proxy(
        self, service: str, srv_type: ServiceTypeInfo, *, persistent: bool = False
    ) -> ServiceProxy:
        proxy = ServiceProxy(
            self.resolve_name(service),
            srv_type,
            self.master,
            persistent=persistent,
            limits=self.limits,
        )
        with self._lock:
            self._proxies.append(proxy)
        return proxy

    # --- TCPROS dispatch --------------------------------------------------------------------
    def _dispatch(self, sock: socket.socket, header: Mapping[str, str], peer: str) -> bool:
        if "topic" in header:
            publisher = self.publisher(header["topic"])
            if publisher is None:
                reason = f"[{self.name}] is not a publisher of [{header['topic']}]"
            else:
                publisher.accept(sock, header, peer, self._next_connection_id())
                return True
        elif "service" in header:
            with self._lock:
                server = self._services.get(header["service"])
            if server is None:
                reason = f"[{self.name}] does not provide service [{header['service']}]"
            else:
                server.serve(sock, header, peer)
                return False
        else:
            reason = "connection header names neither a topic nor a service"
        log.warning("TCPROS peer %s (%s): %s", peer, header.get("callerid", "?"), reason)
        write_header(sock, error_header(reason))
        return False

    # --- parameters -------------------------------------------------------------------------
    def get_param(self, key: str, default: Any = _MISSING) -> Any:
        """The parameter's value (a dict for a namespace); ``default`` or KeyError if unset."""
        try:
            return self.master.get_param(self.resolve_name(key))
        except KeyError:
            if default is _MISSING:
                raise
            return default

    def set_param(self, key: str, value: Any) -> None:
        name = self.resolve_name(key)
        self.master.set_param(name, value)
        with self._lock:
            self._params_set[name] = value

    def has_param(self, key: str) -> bool:
        return self.master.has_param(self.resolve_name(key))

    def delete_param(self, key: str) -> None:
        name = self.resolve_name(key)
        self.master.delete_param(name)
        with self._lock:
            self._params_set.pop(name, None)

    def search_param(self, key: str) -> str | None:
        """Search upwards from this node's namespace; the found global key, or None."""
        return self.master.search_param(key)

    def get_param_names(self) -> list[str]:
        return self.master.get_param_names()

    def subscribe_param(self, key: str, callback: ParamCallback) -> Any:
        """Call ``callback(key, value)`` on changes at or below ``key``; returns the current
        value (``{}`` when unset). A deleted parameter is reported with the value ``{}``."""
        name = self.resolve_name(key)
        with self._lock:
            self._check_running()
            self._param_callbacks.setdefault(name, []).append(callback)
        return self.master.subscribe_param(self.uri, name)

    def param_updated(self, key: str, value: Any) -> None:
        key = canonicalize(key)
        with self._lock:
            matching = [
                callback
                for subscribed, callbacks in self._param_callbacks.items()
                if key == subscribed
                or key.startswith(subscribed.rstrip("/") + "/")
                or subscribed.startswith(key + "/")
                for callback in callbacks
            ]
        for callback in matching:
            try:
                callback(key, value)
            except Exception:
                log.exception("parameter callback for %s failed", key)

    # --- a new master ------------------------------------------------------------------------
    def reregister(self) -> None:
        """Register everything of this node with the master again (a restarted master
        knows nothing of it): parameters, publishers, subscribers, services, parameter
        subscriptions."""
        with self._lock:
            params = dict(self._params_set)
            param_keys = list(self._param_callbacks)
        for name, value in params.items():
            self.master.set_param(name, value)
        for publisher in self.publishers:
            self.master.register_publisher(publisher.topic, publisher.msg_type.name, self.uri)
        for subscriber in self.subscribers:
            uris = self.master.register_subscriber(
                subscriber.topic, subscriber.msg_type.name, self.uri
            )
            subscriber.update_publishers(uris)
        for server in self.services:
            self.master.register_service(server.service, self._service_uri, self.uri)
        for key in param_keys:
            self.master.subscribe_param(self.uri, key)
        log.warning(
            "registered again with %s: %d parameters, %d publishers, %d subscribers, %d services",
            self.master_uri,
            len(params),
            len(self.publishers),
            len(self.subscribers),
            len(self.services),
        )

    # --- lifecycle --------------------------------------------------------------------------
    def _check_running(self) -> None:
        if self._shutdown_started:
            raise Ros1Error(f"node {self.name} is shut down")

    def _master_timeout(self) -> float | None:
        """During shutdown, master calls share a fixed budget; otherwise the usual timeout."""
        if not self._shutdown_started:
            return None
        return self._shutdown_deadline - time.monotonic()

    @contextlib.contextmanager
    def registering_together(self) -> Iterator[None]:
        """The registrations this thread makes inside the block (advertise, subscribe,
        advertise_service) go to the master together as the block ends, in one request
        (system.multicall) instead of one each; a master that serves no multicall gets
        them one by one. A failed one raises MasterError there, as it would have at once."""
        pending: list[_Call] = []
        self._together.calls = pending
        try:
            yield
        finally:
            self._together.calls = None
        self._send_together(pending)

    def _register(
        self, method: str, args: tuple[Any, ...], then: Callable[[Any], None] | None = None
    ) -> None:
        grouped: list[_Call] | None = getattr(self._together, "calls", None)
        if grouped is not None:
            grouped.append(_Call(method, args, then))
            return
        value = self.master.call(method, *args)
        if then is not None:
            then(value)

    def _send_together(self, calls: list[_Call], timeout: float | None = None) -> None:
        """Send `calls` in one request; raise the first one's MasterError, if one failed."""
        if not calls:
            return
        try:
            values = self.master.call_together([(c.method, c.args) for c in calls], timeout)
        except MulticallUnsupportedError:
            values = [self.master.call(c.method, *c.args, timeout=timeout) for c in calls]
        for call, value in zip(calls, values, strict=True):
            if isinstance(value, MasterError):
                raise value
            if call.then is not None:
                call.then(value)

    def _unregister(self, method: str, *args: Any) -> None:
        grouped: list[_Call] | None = getattr(self._together, "calls", None)
        if grouped is not None:
            grouped.append(_Call(method, args))
            return
        timeout = self._master_timeout()
        if timeout is not None and timeout <= 0:
            return
        try:
            self.master.call(method, *args, timeout=timeout)
        except (MasterError, OSError) as exc:
            log.info("%s%s: %s", method, args, exc)

    def _release_publisher(self, publisher: Publisher) -> None:
        with self._lock:
            self._publishers.pop(publisher.topic, None)
        self._unregister("unregisterPublisher", publisher.topic, self.uri)

    def _release_subscriber(self, subscriber: Subscriber) -> None:
        with self._lock:
            self._subscribers.pop(subscriber.topic, None)
        self._unregister("unregisterSubscriber", subscriber.topic, self.uri)

    def _release_service(self, server: ServiceServer) -> None:
        with self._lock:
            self._services.pop(server.service, None)
        self._unregister("unregisterService", server.service, self._service_uri)

    def on_shutdown(self, callback: Callable[[str], None]) -> None:
        """``callback(reason)`` runs once the node has shut down (e.g. after ``rosnode kill``)."""
        with self._lock:
            self._shutdown_callbacks.append(callback)

    def on_shutdown_request(self, handler: Callable[[str], None]) -> None:
        """Hand a peer's shutdown request (``rosnode kill``: the Slave API's ``shutdown``)
        to ``handler(reason)`` instead of shutting down at once: the node's owner stops its
        own work first, then calls ``shutdown``, so nothing it still does meets a node
        already gone. ``handler`` runs on the request's thread and must not block."""
        with self._lock:
            self._shutdown_request_handler = handler

    def request_shutdown(self, reason: str) -> None:
        """A peer asked this node to shut down: the handler of ``on_shutdown_request``
        decides when; without one the node shuts down now, on a thread of its own (the
        request's thread is one of the servers ``shutdown`` stops)."""
        with self._lock:
            handler = self._shutdown_request_handler
        if handler is not None:
            handler(reason)
            return
        threading.Thread(target=self.shutdown, args=(reason,), daemon=True).start()

    @property
    def is_shutdown(self) -> bool:
        return self._stopped.is_set()

    def wait_for_shutdown(self, timeout: float | None = None) -> bool:
        return self._stopped.wait(timeout)

    def shutdown(self, reason: str = "node shutdown") -> None:
        """Unregister everything from the master (within SHUTDOWN_BUDGET_S), close every
        connection, stop the servers (and the embedded master, if this node started one)."""
        with self._lock:
            if self._shutdown_started:
                return
            self._shutdown_started = True
            self._shutdown_deadline = time.monotonic() + SHUTDOWN_BUDGET_S
            self.shutdown_reason = reason
        log.info("node %s shutting down: %s", self.name, reason)
        if self._rosout_handler is not None:
            logging.getLogger(self._rosout_logger).removeHandler(self._rosout_handler)
        handles: list[Publisher | Subscriber | ServiceServer] = [
            *self.publishers,
            *self.subscribers,
            *self.services,
        ]
        with self._lock:
            param_keys, self._param_callbacks = list(self._param_callbacks), {}
            proxies, self._proxies = self._proxies, []
        unregistrations: list[_Call] = []
        self._together.calls = unregistrations
        try:
            for handle in handles:
                handle.close()
            for key in param_keys:
                self._unregister("unsubscribeParam", self.uri, key)
        finally:
            self._together.calls = None
        self._unregister_together(unregistrations)
        for proxy in proxies:
            proxy.close()
        self._tcpros.close()
        self._slave.stop()
        if self.embedded_master is not None:
            self.embedded_master.shutdown()
        self._stopped.set()
        with self._lock:
            callbacks = list(self._shutdown_callbacks)
        for callback in callbacks:
            try:
                callback(reason)
            except Exception:
                log.exception("shutdown callback failed")

    def _unregister_together(self, calls: list[_Call]) -> None:
        """Shutdown's unregistrations, in one request within the shutdown budget; what
        fails is logged (the node is going either way)."""
        timeout = self._master_timeout()
        if not calls or (timeout is not None and timeout <= 0):
            return
        try:
            self._send_together(calls, timeout)
        except (MasterError, OSError) as exc:
            log.info("unregistering %d names: %s", len(calls), exc)

    def __enter__(self) -> Node:
        return self

    def __exit__(self, *exc: object) -> None:
        self.shutdown()
