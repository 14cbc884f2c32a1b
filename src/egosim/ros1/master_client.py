"""Client of the Master API and the Parameter Server API (ROS wiki: Master_API,
Parameter Server API). Every call carries the caller's id; results are unwrapped from the
``[code, statusMessage, value]`` triple, and a code other than 1 raises MasterError."""

from __future__ import annotations

import xmlrpc.client
from collections.abc import Sequence
from typing import Any, cast

from . import rpc
from .errors import (
    MasterError,
    MasterUnreachableError,
    MulticallUnsupportedError,
    PeerUnreachableError,
)
from .rpc import StatusCode


class MasterClient:
    def __init__(self, master_uri: str, caller_id: str, timeout: float = 5.0) -> None:
        self.master_uri = master_uri
        self.caller_id = caller_id
        self.timeout = timeout

    def _raw(self, method: str, *args: Any, timeout: float | None = None) -> list[Any]:
        try:
            return cast(
                list[Any],
                rpc.call(
                    self.master_uri,
                    method,
                    self.caller_id,
                    *args,
                    timeout=self.timeout if timeout is None else timeout,
                ),
            )
        except PeerUnreachableError as exc:
            raise MasterUnreachableError(str(exc)) from exc

    def call(self, method: str, *args: Any, timeout: float | None = None) -> Any:
        """The value of the Master API call `method` (MasterError for a code other than 1)."""
        code, message, value = self._raw(method, *args, timeout=timeout)
        if code != StatusCode.SUCCESS:
            raise MasterError(f"{method}{args}: {message}")
        return value

    def call_together(
        self, calls: Sequence[tuple[str, tuple[Any, ...]]], timeout: float | None = None
    ) -> list[Any]:
        """Several Master API calls in one request (XML-RPC's system.multicall, which
        rosmaster and the embedded master serve): per call, in order, its value or the
        MasterError it gives. MulticallUnsupportedError: the master serves no multicall."""
        batch = [{"methodName": name, "params": [self.caller_id, *args]} for name, args in calls]
        try:
            replies = rpc.call(
                self.master_uri,
                "system.multicall",
                batch,
                timeout=self.timeout if timeout is None else timeout,
            )
        except PeerUnreachableError as exc:
            raise MasterUnreachableError(str(exc)) from exc
        except xmlrpc.client.Fault as fault:
            raise MulticallUnsupportedError(f"{self.master_uri}: {fault.faultString}") from fault
        values: list[Any] = []
        for (method, args), entry in zip(calls, replies, strict=True):
            if isinstance(entry, dict):  # the call raised: a fault in its place
                values.append(MasterError(f"{method}{args}: {entry.get('faultString')}"))
                continue
            code, message, value = entry[0]
            failed = code != StatusCode.SUCCESS
            values.append(MasterError(f"{method}{args}: {message}") if failed else value)
        return values

    # Master API: registration
    def register_service(self, service: str, service_api: str, caller_api: str) -> None:
        self.call("registerService", service, service_api, caller_api)

    def unregister_service(
        self, service: str, service_api: str, timeout: float | None = None
    ) -> int:
        return cast(int, self.call("unregisterService", service, service_api, timeout=timeout))

    def register_subscriber(self, topic: str, topic_type: str, caller_api: str) -> list[str]:
        return list(self.call("registerSubscriber", topic, topic_type, caller_api))

    def unregister_subscriber(
        self, topic: str, caller_api: str, timeout: float | None = None
    ) -> int:
        return cast(int, self.call("unregisterSubscriber", topic, caller_api, timeout=timeout))

    def register_publisher(self, topic: str, topic_type: str, caller_api: str) -> list[str]:
        return list(self.call("registerPublisher", topic, topic_type, caller_api))

    def unregister_publisher(
        self, topic: str, caller_api: str, timeout: float | None = None
    ) -> int:
        return cast(int, self.call("unregisterPublisher", topic, caller_api, timeout=timeout))

    # Master API: name service and system state
    def lookup_node(self, node_name: str) -> str:
        return cast(str, self.call("lookupNode", node_name))

    def get_published_topics(self, subgraph: str = "") -> list[tuple[str, str]]:
        return [(topic, kind) for topic, kind in self.call("getPublishedTopics", subgraph)]

    def get_topic_types(self) -> list[tuple[str, str]]:
        return [(topic, kind) for topic, kind in self.call("getTopicTypes")]

    def get_system_state(self) -> tuple[list[Any], list[Any], list[Any]]:
        publishers, subscribers, services = self.call("getSystemState")
        return publishers, subscribers, services

    def get_uri(self, timeout: float | None = None) -> str:
        return cast(str, self.call("getUri", timeout=timeout))

    def get_pid(self, timeout: float | None = None) -> int:
        return int(self.call("getPid", timeout=timeout))

    def lookup_service(self, service: str) -> str:
        return cast(str, self.call("lookupService", service))

    # Parameter Server API
    def delete_param(self, key: str) -> None:
        self.call("deleteParam", key)

    def set_param(self, key: str, value: Any) -> None:
        self.call("setParam", key, value)

    def get_param(self, key: str) -> Any:
        """The value (a dict for a namespace); KeyError when the key is not set."""
        code, _message, value = self._raw("getParam", key)
        if code != StatusCode.SUCCESS:
            raise KeyError(key)
        return value

    def search_param(self, key: str) -> str | None:
        code, _message, value = self._raw("searchParam", key)
        return value if code == StatusCode.SUCCESS and value else None

    def subscribe_param(self, caller_api: str, key: str) -> Any:
        return self.call("subscribeParam", caller_api, key)

    def unsubscribe_param(self, caller_api: str, key: str, timeout: float | None = None) -> int:
        return cast(int, self.call("unsubscribeParam", caller_api, key, timeout=timeout))

    def has_param(self, key: str) -> bool:
        return bool(self.call("hasParam", key))

    def get_param_names(self) -> list[str]:
        return list(self.call("getParamNames"))
