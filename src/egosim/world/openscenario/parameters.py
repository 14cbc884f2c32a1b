"""Parameters: declarations with their types and constraints, `$name` and `${...}`
attribute values, and the scopes they resolve in (the scenario's, a catalogue entry's).

Every attribute of an OpenSCENARIO element may be a literal, a reference `$name` or an
expression `${...}`; `Scope.resolve` turns it into its value. Declarations are read in
file order, so a value may use the parameters declared before it; values from outside
(a batch case, a ParameterValueDistribution) replace the declared ones before the later
declarations are worked out, so derived parameters follow them.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

from egosim.world.openscenario.expressions import ExpressionError, Value, evaluate
from egosim.world.openscenario.xmltree import Node
from egosim.world.scenario.errors import ScenarioError

_NUMBER_TYPES = ("double", "int", "integer", "unsignedInt", "unsignedShort")
PARAMETER_TYPES = (*_NUMBER_TYPES, "string", "boolean", "dateTime")


def text_of(value: Value) -> str:
    """A value as attribute text: true/false, integers without a decimal point."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return str(int(value)) if value.is_integer() and abs(value) < 1e15 else repr(value)
    return str(value)


def typed(value: Value, kind: str, where: Node, name: str) -> Value:
    """`value` as a parameter of type `kind` (double, int, boolean, string, ...)."""
    try:
        if kind == "double":
            return float(value) if not isinstance(value, str) else float(value.strip())
        if kind in ("int", "integer", "unsignedInt", "unsignedShort"):
            number = float(value) if not isinstance(value, str) else float(value.strip())
            if not math.isfinite(number):
                raise ValueError(f"{value!r}")
            result = float(math.floor(number + 0.5))
            if kind not in {"int", "integer"} and result < 0:
                raise ValueError(f"{value!r} is negative")
            return result
        if kind == "boolean":
            if isinstance(value, bool):
                return value
            text = str(value).strip().lower()
            if text not in ("true", "false", "1", "0"):
                raise ValueError(f"{value!r}")
            return text in ("true", "1")
    except ValueError as error:
        raise where.error(f"parameter {name!r}: {error} is not a {kind}") from None
    return text_of(value)


class Scope:
    """Parameter values by name, falling back to an enclosing scope."""

    def __init__(self, values: Mapping[str, Value] | None = None, parent: Scope | None = None):
        self.values: dict[str, Value] = dict(values or {})
        self.parent = parent

    def find(self, name: str) -> Value | None:
        scope: Scope | None = self
        while scope is not None:
            if name in scope.values:
                return scope.values[name]
            scope = scope.parent
        return None

    def lookup(self, name: str) -> Value:
        value = self.find(name)
        if value is None:
            raise ExpressionError(f"no parameter {name!r} is declared")
        return value

    def resolve(self, text: str, where: Node, attribute: str) -> Value:
        """The value of an attribute's text: a literal as it is, `$name`, or `${expr}`."""
        stripped = text.strip()
        try:
            if stripped.startswith("${") and stripped.endswith("}"):
                return evaluate(stripped[2:-1], self.lookup)
            if stripped.startswith("$") and len(stripped) > 1:
                return self.lookup(stripped[1:])
        except ExpressionError as error:
            raise where.error(f"{attribute}: {error}") from None
        return text

    def child(self, values: Mapping[str, Value] | None = None) -> Scope:
        return Scope(values, self)


@dataclass(frozen=True)
class Declared:
    """A declared parameter: its type and where it is declared."""

    name: str
    kind: str
    node: Node


def declare(
    declarations: Node | None,
    scope: Scope,
    overrides: Mapping[str, str] | None = None,
    tag: str = "ParameterDeclaration",
    type_attribute: str = "parameterType",
) -> list[Declared]:
    """Read <ParameterDeclarations> (or <VariableDeclarations>) into `scope`, in order;
    `overrides` replace declared values (text, as assignments give them)."""
    overrides = overrides or {}
    declared: list[Declared] = []
    if declarations is None:
        return declared
    for node in declarations.children(tag):
        name = node.get("name")
        kind = node.get(type_attribute)
        if not name:
            raise node.error("needs a name")
        if kind not in PARAMETER_TYPES:
            raise node.error(f"parameter {name!r}: unknown {type_attribute} {kind!r}")
        text = overrides.get(name, node.get("value"))
        if text is None:
            raise node.error(f"parameter {name!r} needs a value")
        value = typed(scope.resolve(text, node, "value"), kind, node, name)
        scope.values[name] = value
        check_constraints(node, name, value, scope)
        declared.append(Declared(name, kind, node))
    unknown = sorted(set(overrides) - {d.name for d in declared})
    if unknown and tag == "ParameterDeclaration":
        raise declarations.error(f"no parameter declared for {', '.join(unknown)}")
    return declared


def compare(rule: str, left: Value, right: Value) -> bool:
    """An OpenSCENARIO Rule (equalTo, greaterThan, lessThan, greaterOrEqual,
    lessOrEqual, notEqualTo) between two values, numerically where both are numbers."""
    a: float | str
    b: float | str
    try:
        a, b = float(left), float(right)
    except ValueError:
        a, b = text_of(left), text_of(right)
    if rule == "equalTo":
        return (
            a == b
            if isinstance(a, str)
            else abs(float(a) - float(b)) <= 1e-9 * max(1.0, abs(float(a)))
        )
    if rule == "notEqualTo":
        return not compare("equalTo", left, right)
    if isinstance(a, str) or isinstance(b, str):
        return False
    return {
        "greaterThan": a > b,
        "lessThan": a < b,
        "greaterOrEqual": a >= b,
        "lessOrEqual": a <= b,
    }.get(rule, False)


RULES = ("equalTo", "greaterThan", "lessThan", "greaterOrEqual", "lessOrEqual", "notEqualTo")


def check_constraints(node: Node, name: str, value: Value, scope: Scope) -> None:
    """A value must meet every constraint of at least one <ConstraintGroup>."""
    groups = node.children("ConstraintGroup")
    if not groups:
        return
    for group in groups:
        if all(_meets(c, value, scope) for c in group.children()):
            return
    raise node.error(f"parameter {name!r} = {text_of(value)} breaks its constraints")


def _meets(constraint: Node, value: Value, scope: Scope) -> bool:
    if constraint.tag == "ValueConstraint":
        rule = constraint.get("rule") or ""
        if rule not in RULES:
            raise constraint.error(f"unknown rule {rule!r}")
        limit = scope.resolve(constraint.get("value") or "", constraint, "value")
        return compare(rule, value, limit)
    if constraint.tag == "RangeConstraint":
        lower = scope.resolve(constraint.get("lowerLimit") or "", constraint, "lowerLimit")
        upper = scope.resolve(constraint.get("upperLimit") or "", constraint, "upperLimit")
        return compare("greaterOrEqual", value, lower) and compare("lessOrEqual", value, upper)
    raise constraint.error("is not a constraint")


def assignments(node: Node | None, scope: Scope) -> dict[str, str]:
    """<ParameterAssignments> as name -> text, each value resolved in `scope`."""
    if node is None:
        return {}
    result = {}
    for assignment in node.children("ParameterAssignment"):
        name = assignment.get("parameterRef")
        if not name:
            raise assignment.error("needs a parameterRef")
        result[name] = text_of(scope.resolve(assignment.get("value") or "", assignment, "value"))
    return result


def must(value: Value | None, node: Node, attribute: str) -> Value:
    if value is None:
        raise node.error(f"needs attribute {attribute!r}")
    return value


__all__ = [
    "RULES",
    "Declared",
    "ScenarioError",
    "Scope",
    "assignments",
    "compare",
    "declare",
    "text_of",
    "typed",
]
