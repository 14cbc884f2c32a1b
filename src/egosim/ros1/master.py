"""An embedded ROS master: the Master API and the Parameter Server API served over XML-RPC on a
thread (ROS wiki: Master_API, Parameter Server API), interchangeable with rosmaster for
rospy/roscpp nodes and the command-line tools."""

from __future__ import annotations

import logging
import os
import threading
import uuid
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any
from urllib.parse import urlsplit, urlunsplit

from .names import SEP, canonicalize, namespace_of, resolve
from .network import DEFAULT_MASTER_URI, master_bind_address
from .notifier import Notifier
from .param_tree import ParameterTree
from .rpc import Reply, StatusCode, XmlRpcServer, reply

log = logging.getLogger(__name__)

MASTER_CALLER_ID = "/master"
ANY_TYPE = "*"


def _ok(message: str, value: Any) -> Reply:
    return reply(StatusCode.SUCCESS, message, value)


def _as_namespace(key: str) -> str:
    """Keys of parameter subscriptions and updates end with a separator (rosmaster does so)."""
    return key if key == SEP else canonicalize(key) + SEP


@dataclass
class _Registrations:
    """Who publishes, subscribes, provides: name -> {caller_id: api}."""

    publishers: dict[str, dict[str, str]] = field(default_factory=dict)
    subscribers: dict[str, dict[str, str]] = field(default_factory=dict)
    services: dict[str, dict[str, str]] = field(default_factory=dict)
    param_subscribers: dict[str, dict[str, str]] = field(default_factory=dict)
    topic_types: dict[str, str] = field(default_factory=dict)
    nodes: dict[str, str] = field(default_factory=dict)

    def tables(self) -> tuple[dict[str, dict[str, str]], ...]:
        return self.publishers, self.subscribers, self.services, self.param_subscribers

    def add(self, table: dict[str, dict[str, str]], name: str, caller_id: str, api: str) -> None:
        table.setdefault(name, {})[caller_id] = api

    def remove(self, table: dict[str, dict[str, str]], name: str, caller_id: str) -> bool:
        entries = table.get(name, {})
        if caller_id not in entries:
            return False
        del entries[caller_id]
        if not entries:
            del table[name]
        return True

    def forget_node(self, caller_id: str) -> list[str]:
        """Drop every registration of ``caller_id``; return the topics it published."""
        published = [t for t, nodes in self.publishers.items() if caller_id in nodes]
        for table in self.tables():
            for name in [n for n, nodes in table.items() if caller_id in nodes]:
                self.remove(table, name, caller_id)
        self.nodes.pop(caller_id, None)
        return published

    def drop_node_if_unused(self, caller_id: str) -> None:
        if not any(caller_id in nodes for table in self.tables() for nodes in table.values()):
            self.nodes.pop(caller_id, None)


class Master:
    """``Master(uri).start()`` serves at the host/port of ``uri``; ``shutdown()`` stops it."""

    def __init__(self, uri: str = DEFAULT_MASTER_URI, bind_host: str | None = None) -> None:
        host, port = master_bind_address(uri)
        self._bind = (bind_host or host, port)
        self._requested_uri = uri
        self._lock = threading.RLock()
        self._reg = _Registrations()
        self._params = ParameterTree()
        self._params.set("/run_id", str(uuid.uuid1()))
        self._notifier = Notifier(MASTER_CALLER_ID)
        self._server: XmlRpcServer | None = None
        self._service_added = threading.Condition(self._lock)
        self._holding_lookups = False

    @property
    def uri(self) -> str:
        """The master's URI, with the real port once started on port 0."""
        parts = urlsplit(self._requested_uri)
        if self._server is None:
            return self._requested_uri
        netloc = f"{parts.hostname}:{self._server.port}"
        return urlunsplit((parts.scheme or "http", netloc, parts.path or "/", "", ""))

    def start(self) -> Master:
        """Bind and serve; OSError (e.g. address in use) if another master holds the port."""
        server = XmlRpcServer(self._bind, name="ros master")
        server.register_api(self.api())
        server.start()
        self._server = server
        log.info("embedded ROS master serving at %s", self.uri)
        return self

    def hold_lookups(self, holding: bool) -> None:
        """While holding, a lookup of a service no node provides yet waits until one does
        (or the hold ends, and it gets the usual error): a node that starts before the
        nodes it needs (a batch case's stack, before its simulator) then goes on the moment
        they are up instead of at its next try (rospy's wait_for_service tries every 0.3 s)."""
        with self._lock:
            self._holding_lookups = holding
            self._service_added.notify_all()

    def shutdown(self) -> None:
        self.hold_lookups(False)
        self._notifier.close()
        if self._server is not None:
            self._server.stop()
            self._server = None

    def __enter__(self) -> Master:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.shutdown()

    def api(self) -> dict[str, Callable[..., Reply]]:
        """The Master and Parameter Server API's functions, by their names."""
        return {
            "registerService": self.register_service,
            "unregisterService": self.unregister_service,
            "registerSubscriber": self.register_subscriber,
            "unregisterSubscriber": self.unregister_subscriber,
            "registerPublisher": self.register_publisher,
            "unregisterPublisher": self.unregister_publisher,
            "lookupNode": self.lookup_node,
            "getPublishedTopics": self.get_published_topics,
            "getTopicTypes": self.get_topic_types,
            "getSystemState": self.get_system_state,
            "getUri": self.get_uri,
            "lookupService": self.lookup_service,
            "getPid": self.get_pid,
            "deleteParam": self.delete_param,
            "setParam": self.set_param,
            "getParam": self.get_param,
            "searchParam": self.search_param,
            "subscribeParam": self.subscribe_param,
            "unsubscribeParam": self.unsubscribe_param,
            "hasParam": self.has_param,
            "getParamNames": self.get_param_names,
        }

    @staticmethod
    def _resolve(name: str, caller_id: str) -> str:
        return resolve(name, namespace_of(caller_id), caller_id)

    def _register_node(self, caller_id: str, caller_api: str) -> None:
        """A second node under a known name replaces the first, which is told to shut down."""
        if not isinstance(caller_api, str) or not caller_api.startswith(("http://", "https://")):
            # Every later notification goes to this API: refuse what cannot be called.
            raise ValueError(f"caller_api must be an http:// XML-RPC URI, got {caller_api!r}")
        previous = self._reg.nodes.get(caller_id)
        if previous is not None and previous != caller_api:
            log.info(
                "node %s re-registered from %s; shutting down %s", caller_id, caller_api, previous
            )
            for topic in self._reg.forget_node(caller_id):
                self._notify_publishers_changed(topic)
            self._notifier.send(
                previous, "shutdown", f"new node registered with same name {caller_id}"
            )
        self._reg.nodes[caller_id] = caller_api

    def _notify_publishers_changed(self, topic: str) -> None:
        publishers = list(self._reg.publishers.get(topic, {}).values())
        for api in self._reg.subscribers.get(topic, {}).values():
            self._notifier.send(api, "publisherUpdate", topic, publishers)

    # Master API: register/unregister
    def register_service(
        self, caller_id: str, service: str, service_api: str, caller_api: str
    ) -> Reply:
        service = self._resolve(service, caller_id)
        with self._lock:
            self._register_node(caller_id, caller_api)
            self._reg.services[service] = {caller_id: service_api}
            self._service_added.notify_all()
        return _ok(f"Registered [{caller_id}] as provider of [{service}]", 1)

    def unregister_service(self, caller_id: str, service: str, service_api: str) -> Reply:
        service = self._resolve(service, caller_id)
        with self._lock:
            if self._reg.services.get(service, {}).get(caller_id) != service_api:
                return _ok(f"[{caller_id}] is not a provider of [{service}]", 0)
            self._reg.remove(self._reg.services, service, caller_id)
            self._reg.drop_node_if_unused(caller_id)
        return _ok(f"Unregistered [{caller_id}] as provider of [{service}]", 1)

    def _set_topic_type(self, topic: str, topic_type: str) -> None:
        if topic_type != ANY_TYPE or topic not in self._reg.topic_types:
            self._reg.topic_types[topic] = topic_type

    def register_subscriber(
        self, caller_id: str, topic: str, topic_type: str, caller_api: str
    ) -> Reply:
        topic = self._resolve(topic, caller_id)
        with self._lock:
            self._register_node(caller_id, caller_api)
            self._reg.add(self._reg.subscribers, topic, caller_id, caller_api)
            self._set_topic_type(topic, topic_type)
            publishers = list(self._reg.publishers.get(topic, {}).values())
        return _ok(f"Subscribed to [{topic}]", publishers)

    def unregister_subscriber(self, caller_id: str, topic: str, caller_api: str) -> Reply:
        topic = self._resolve(topic, caller_id)
        with self._lock:
            if self._reg.subscribers.get(topic, {}).get(caller_id) != caller_api:
                return _ok(f"[{caller_id}] is not a subscriber of [{topic}]", 0)
            self._reg.remove(self._reg.subscribers, topic, caller_id)
            self._reg.drop_node_if_unused(caller_id)
        return _ok(f"Unsubscribed from [{topic}]", 1)

    def register_publisher(
        self, caller_id: str, topic: str, topic_type: str, caller_api: str
    ) -> Reply:
        topic = self._resolve(topic, caller_id)
        with self._lock:
            self._register_node(caller_id, caller_api)
            self._reg.add(self._reg.publishers, topic, caller_id, caller_api)
            self._set_topic_type(topic, topic_type)
            subscribers = list(self._reg.subscribers.get(topic, {}).values())
            self._notify_publishers_changed(topic)
        return _ok(f"Registered [{caller_id}] as publisher of [{topic}]", subscribers)

    def unregister_publisher(self, caller_id: str, topic: str, caller_api: str) -> Reply:
        topic = self._resolve(topic, caller_id)
        with self._lock:
            if self._reg.publishers.get(topic, {}).get(caller_id) != caller_api:
                return _ok(f"[{caller_id}] is not a publisher of [{topic}]", 0)
            self._reg.remove(self._reg.publishers, topic, caller_id)
            self._reg.drop_node_if_unused(caller_id)
            self._notify_publishers_changed(topic)
        return _ok(f"Unregistered [{caller_id}] as publisher of [{topic}]", 1)

    # Master API: name service and system state
    def lookup_node(self, caller_id: str, node_name: str) -> Reply:
        node_name = self._resolve(node_name, caller_id)
        with self._lock:
            api = self._reg.nodes.get(node_name)
        if api is None:
            return reply(StatusCode.ERROR, f"unknown node [{node_name}]", "")
        return _ok(f"node api for [{node_name}]", api)

    def get_published_topics(self, caller_id: str, subgraph: str) -> Reply:
        prefix = _as_namespace(self._resolve(subgraph, caller_id)) if subgraph else SEP
        with self._lock:
            topics = [
                [topic, self._reg.topic_types.get(topic, ANY_TYPE)]
                for topic in self._reg.publishers
                if (topic + SEP).startswith(prefix)
            ]
        return _ok("current topics", topics)

    def get_topic_types(self, caller_id: str) -> Reply:
        with self._lock:
            return _ok(
                "current topic types", [list(item) for item in self._reg.topic_types.items()]
            )

    def get_system_state(self, caller_id: str) -> Reply:
        with self._lock:
            state = [
                [[name, list(nodes)] for name, nodes in table.items()]
                for table in (self._reg.publishers, self._reg.subscribers, self._reg.services)
            ]
        return _ok("current system state", state)

    def get_uri(self, caller_id: str) -> Reply:
        return _ok("", self.uri)

    def lookup_service(self, caller_id: str, service: str) -> Reply:
        service = self._resolve(service, caller_id)
        with self._lock:
            while not (providers := list(self._reg.services.get(service, {}).values())):
                if not self._holding_lookups:
                    break
                self._service_added.wait()
        if not providers:
            return reply(StatusCode.ERROR, f"no provider for [{service}]", "")
        return _ok(f"rosrpc URI: [{providers[0]}]", providers[0])

    def get_pid(self, caller_id: str) -> Reply:
        return _ok("", os.getpid())

    # Parameter Server API
    def _param_changed(self, caller_id: str, key: str) -> None:
        """Tell parameter subscribers about a change at ``key``: subscribers of ``key`` or of a
        namespace above it get the changed value; subscribers below it get their new value,
        or ``{}`` where the change removed it."""
        changed = _as_namespace(key)
        for subscribed, nodes in self._reg.param_subscribers.items():
            if changed.startswith(subscribed):
                update_key = changed
            elif subscribed.startswith(changed):
                update_key = subscribed
            else:
                continue
            try:
                value = self._params.get(update_key)
            except KeyError:
                value = {}
            for node, api in nodes.items():
                if node != caller_id:
                    self._notifier.send(api, "paramUpdate", update_key, value)

    def delete_param(self, caller_id: str, key: str) -> Reply:
        key = self._resolve(key, caller_id)
        with self._lock:
            try:
                self._params.delete(key)
            except KeyError:
                return reply(StatusCode.ERROR, f"parameter [{key}] is not set", 0)
            self._param_changed(caller_id, key)
        return _ok(f"parameter {key} deleted", 0)

    def set_param(self, caller_id: str, key: str, value: Any) -> Reply:
        key = self._resolve(key, caller_id)
        with self._lock:
            try:
                self._params.set(key, value)
            except TypeError as exc:
                return reply(StatusCode.ERROR, str(exc), 0)
            self._param_changed(caller_id, key)
        return _ok(f"parameter {key} set", 0)

    def get_param(self, caller_id: str, key: str) -> Reply:
        key = self._resolve(key, caller_id)
        with self._lock:
            try:
                return _ok(f"Parameter [{key}]", self._params.get(key))
            except KeyError:
                return reply(StatusCode.ERROR, f"Parameter [{key}] is not set", 0)

    def search_param(self, caller_id: str, key: str) -> Reply:
        with self._lock:
            found = self._params.search(caller_id, key)
        if found is None:
            return reply(
                StatusCode.ERROR, f"Cannot find parameter [{key}] in an upwards search", ""
            )
        return _ok(f"Found [{found}]", found)

    def subscribe_param(self, caller_id: str, caller_api: str, key: str) -> Reply:
        key = self._resolve(key, caller_id)
        with self._lock:
            self._register_node(caller_id, caller_api)
            self._reg.add(self._reg.param_subscribers, _as_namespace(key), caller_id, caller_api)
            try:
                value = self._params.get(key)
            except KeyError:
                value = {}
        return _ok(f"Subscribed to parameter [{key}]", value)

    def unsubscribe_param(self, caller_id: str, caller_api: str, key: str) -> Reply:
        key = self._resolve(key, caller_id)
        with self._lock:
            removed = self._reg.remove(self._reg.param_subscribers, _as_namespace(key), caller_id)
            self._reg.drop_node_if_unused(caller_id)
        return _ok(f"Unsubscribed from parameter [{key}]", int(removed))

    def has_param(self, caller_id: str, key: str) -> Reply:
        key = self._resolve(key, caller_id)
        with self._lock:
            return _ok(key, self._params.has(key))

    def get_param_names(self, caller_id: str) -> Reply:
        with self._lock:
            return _ok("Parameter names", self._params.names())
