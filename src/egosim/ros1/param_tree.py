"""The parameter store of the embedded master: a tree of namespaces (ROS wiki: Parameter Server).

Setting a dict replaces the subtree at that key; getting a namespace returns it as a dict.
Keys are global names; the master resolves callers' relative and private keys first.
"""

from __future__ import annotations

import copy
import xmlrpc.client
from typing import Any

from .names import SEP, canonicalize


def _parts(key: str) -> list[str]:
    return [part for part in canonicalize(key).split(SEP) if part]


def _check_answerable(value: Any) -> None:
    """TypeError if `value` could not be sent back over XML-RPC (whose ints are 32-bit), so
    that one parameter cannot break getParam for everyone."""
    if isinstance(value, bool):
        return
    if isinstance(value, int) and not xmlrpc.client.MININT <= value <= xmlrpc.client.MAXINT:
        raise TypeError(f"{value} is outside XML-RPC's 32-bit int range")
    if isinstance(value, dict):
        for item in value.values():
            _check_answerable(item)
    elif isinstance(value, list | tuple):
        for item in value:
            _check_answerable(item)


class ParameterTree:
    def __init__(self) -> None:
        self._root: dict[str, Any] = {}

    def set(self, key: str, value: Any) -> None:
        _check_answerable(value)
        parts = _parts(key)
        if not parts:
            if not isinstance(value, dict):
                raise TypeError("the root namespace can only be set to a dict")
            self._root = copy.deepcopy(value)
            return
        node = self._root
        for part in parts[:-1]:
            child = node.get(part)
            if not isinstance(child, dict):
                child = node[part] = {}
            node = child
        node[parts[-1]] = copy.deepcopy(value)

    def get(self, key: str) -> Any:
        """The value at ``key`` (a copy); KeyError if not set."""
        node: Any = self._root
        for part in _parts(key):
            if not isinstance(node, dict) or part not in node:
                raise KeyError(key)
            node = node[part]
        return copy.deepcopy(node)

    def has(self, key: str) -> bool:
        try:
            self.get(key)
        except KeyError:
            return False
        return True

    def delete(self, key: str) -> None:
        parts = _parts(key)
        if not parts:
            raise KeyError("the root namespace cannot be deleted")
        node: Any = self._root
        for part in parts[:-1]:
            if not isinstance(node, dict) or part not in node:
                raise KeyError(key)
            node = node[part]
        if not isinstance(node, dict) or parts[-1] not in node:
            raise KeyError(key)
        del node[parts[-1]]

    def names(self) -> list[str]:
        """Every leaf key (namespaces themselves are not listed, as in rosmaster)."""
        found: list[str] = []

        def walk(prefix: str, node: dict[str, Any]) -> None:
            for name, value in node.items():
                key = prefix + SEP + name
                if isinstance(value, dict):
                    walk(key, value)
                else:
                    found.append(key)

        walk("", self._root)
        return found

    def search(self, namespace: str, key: str) -> str | None:
        """Find ``key`` from ``namespace`` upwards: the first namespace holding the key's first
        element wins, and the full key below it is returned (it may itself be unset)."""
        if key.startswith(SEP):
            return canonicalize(key) if self.has(key) else None
        key_parts = _parts(key)
        if not key_parts:
            return None
        scopes = _parts(namespace)
        for depth in range(len(scopes), -1, -1):
            base = SEP + SEP.join([*scopes[:depth], key_parts[0]])
            if self.has(base):
                return SEP + SEP.join(scopes[:depth] + key_parts)
        return None
