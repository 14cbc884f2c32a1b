"""ROS graph resource names: validation, resolution and command-line remapping (ROS wiki: Names)."""

from __future__ import annotations

import re
from dataclasses import dataclass, field

import yaml

from .errors import InvalidNameError

SEP = "/"
PRIVATE = "~"
# The rule rosgraph applies: a letter, '/' or '~' first, then word characters and '/'.
_VALID = re.compile(r"^[~/A-Za-z][\w/]*$")


def validate_name(name: str) -> str:
    """Return ``name`` if it is a legal graph resource name, else raise InvalidNameError."""
    if not _VALID.match(name) or "//" in name:
        raise InvalidNameError(f"invalid ROS name: {name!r}")
    return name


def canonicalize(name: str) -> str:
    """Drop a trailing separator and duplicate separators (``/a//b/`` -> ``/a/b``)."""
    if not name:
        return name
    prefix = SEP if name.startswith(SEP) else ""
    return prefix + SEP.join(part for part in name.split(SEP) if part)


def namespace_of(name: str) -> str:
    """Namespace of a global name, with a trailing separator (``/a/b`` -> ``/a/``)."""
    name = canonicalize(name)
    if name in ("", SEP):
        return SEP
    return name[: name.rfind(SEP) + 1]


def join(namespace: str, name: str) -> str:
    return canonicalize(namespace + SEP + name) or SEP


def resolve(name: str, namespace: str, node_name: str) -> str:
    """Resolve a global, relative or private (``~``) name to a global name, without remapping."""
    if name == "":
        return canonicalize(namespace) or SEP
    validate_name(name)
    if name.startswith(SEP):
        return canonicalize(name) or SEP
    if name.startswith(PRIVATE):
        return join(node_name, name[1:])
    return join(namespace, name)


@dataclass
class NodeArgs:
    """What a node's command line says about it: special keys, remappings and private params."""

    name: str | None = None
    namespace: str | None = None
    remappings: dict[str, str] = field(default_factory=dict)
    private_params: dict[str, object] = field(default_factory=dict)
    special: dict[str, str] = field(default_factory=dict)
    unparsed: list[str] = field(default_factory=list)


def parse_argv(argv: list[str]) -> NodeArgs:
    """Split ``from:=to`` arguments into special keys (``__name``, ``__ns``, ``__master``,
    ``__ip``, ``__hostname``, ``__log``), private params (``_key:=yaml``) and remappings."""
    args = NodeArgs()
    for arg in argv:
        if ":=" not in arg:
            args.unparsed.append(arg)
            continue
        src, dst = arg.split(":=", 1)
        if src.startswith("__"):
            args.special[src] = dst
        elif src.startswith("_") and len(src) > 1:
            args.private_params[src[1:]] = yaml.safe_load(dst) if dst else ""
        else:
            validate_name(src)
            validate_name(dst)
            args.remappings[src] = dst
    args.name = args.special.get("__name")
    args.namespace = args.special.get("__ns")
    return args


class NameResolver:
    """Resolves names for one node: its namespace, its private namespace and its remappings."""

    def __init__(self, node_name: str, remappings: dict[str, str] | None = None) -> None:
        self.node_name = canonicalize(node_name)
        self.namespace = namespace_of(self.node_name)
        self._remappings = {
            resolve(src, self.namespace, self.node_name): resolve(
                dst, self.namespace, self.node_name
            )
            for src, dst in (remappings or {}).items()
        }

    def resolve(self, name: str, remap: bool = True) -> str:
        resolved = resolve(name, self.namespace, self.node_name)
        if remap:
            return self._remappings.get(resolved, resolved)
        return resolved

    @property
    def remappings(self) -> dict[str, str]:
        return dict(self._remappings)
