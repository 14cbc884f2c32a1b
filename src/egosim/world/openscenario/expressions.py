"""OpenSCENARIO expressions, `${...}` (1.1+): arithmetic, comparisons and logic over
numbers, booleans and `$parameter` references.

Python's own parser reads the expression (the grammar is a subset of Python's once
`$name` is an identifier); only the node types of the standard's grammar are
evaluated: + - * / % and unary -, == != < <= > >=, and/or/not, parentheses, the
functions round floor ceil sqrt pow sin cos tan asin acos atan sign abs max min, and the
constant pi (as esmini and the Euro NCAP files use it).
"""

from __future__ import annotations

import ast
import math
import operator
import re
from collections.abc import Callable, Mapping

Value = float | bool | str

_REFERENCE = re.compile(r"\$([A-Za-z_][A-Za-z0-9_]*)")
_PREFIX = "__p_"

_BINARY: dict[type[ast.operator], Callable[[float, float], float]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.Mod: math.fmod,
}
# Both sides are numbers, or both texts (a text on either side compares as text).
_COMPARE: dict[type[ast.cmpop], Callable[[float | str, float | str], bool]] = {
    ast.Eq: operator.eq,
    ast.NotEq: operator.ne,
    ast.Lt: operator.lt,
    ast.LtE: operator.le,
    ast.Gt: operator.gt,
    ast.GtE: operator.ge,
}


def _sign(x: float) -> float:
    return float((x > 0) - (x < 0))


_FUNCTIONS: dict[str, Callable[..., float]] = {
    "round": lambda x: float(math.floor(x + 0.5)),
    "floor": lambda x: float(math.floor(x)),
    "ceil": lambda x: float(math.ceil(x)),
    "sqrt": math.sqrt,
    "pow": math.pow,
    "sin": math.sin,
    "cos": math.cos,
    "tan": math.tan,
    "asin": math.asin,
    "acos": math.acos,
    "atan": math.atan,
    "sign": _sign,
    "abs": lambda x: float(abs(x)),
    "max": lambda a, b: float(max(a, b)),
    "min": lambda a, b: float(min(a, b)),
}
_CONSTANTS: dict[str, Value] = {"pi": math.pi, "true": True, "false": False}


class ExpressionError(ValueError):
    """An expression that cannot be evaluated; the message says why."""


def references(expression: str) -> list[str]:
    """The parameter names an expression refers to."""
    return _REFERENCE.findall(expression)


def evaluate(expression: str, lookup: Callable[[str], Value]) -> Value:
    """The value of the expression inside `${...}`; `lookup` gives a parameter's value."""
    source = _REFERENCE.sub(lambda m: _PREFIX + m.group(1), expression.strip())
    try:
        tree = ast.parse(source, mode="eval")
    except SyntaxError:
        raise ExpressionError(f"cannot read expression {expression!r}") from None
    try:
        return _value(tree.body, lookup)
    except (ZeroDivisionError, OverflowError, ValueError, TypeError) as error:
        if isinstance(error, ExpressionError):
            raise
        raise ExpressionError(f"expression {expression!r}: {error}") from None


def _number(value: Value) -> float:
    if isinstance(value, bool):
        return float(value)
    if isinstance(value, str):
        try:
            return float(value)
        except ValueError:
            raise ExpressionError(f"{value!r} is not a number") from None
    return float(value)


def _truth(value: Value) -> bool:
    if isinstance(value, str):
        if value in ("true", "false"):
            return value == "true"
        raise ExpressionError(f"{value!r} is not a boolean")
    return bool(value)


def _value(node: ast.expr, lookup: Callable[[str], Value]) -> Value:
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
        return float(node.value)
    if isinstance(node, ast.Name):
        if node.id.startswith(_PREFIX):
            return lookup(node.id[len(_PREFIX) :])
        if node.id in _CONSTANTS:
            return _CONSTANTS[node.id]
        raise ExpressionError(f"unknown name {node.id!r} (parameters are written $name)")
    if isinstance(node, ast.UnaryOp):
        operand = _value(node.operand, lookup)
        if isinstance(node.op, ast.USub):
            return -_number(operand)
        if isinstance(node.op, ast.UAdd):
            return _number(operand)
        if isinstance(node.op, ast.Not):
            return not _truth(operand)
    if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        left, right = _number(_value(node.left, lookup)), _number(_value(node.right, lookup))
        return float(_BINARY[type(node.op)](left, right))
    if isinstance(node, ast.BoolOp):
        values = [_truth(_value(v, lookup)) for v in node.values]
        return all(values) if isinstance(node.op, ast.And) else any(values)
    if isinstance(node, ast.Compare) and len(node.ops) == 1 and type(node.ops[0]) in _COMPARE:
        first = _value(node.left, lookup)
        second = _value(node.comparators[0], lookup)
        if isinstance(first, str) or isinstance(second, str):
            return _COMPARE[type(node.ops[0])](str(first), str(second))
        return _COMPARE[type(node.ops[0])](_number(first), _number(second))
    if (
        isinstance(node, ast.Call)
        and isinstance(node.func, ast.Name)
        and node.func.id in _FUNCTIONS
        and not node.keywords
    ):
        arguments = [_number(_value(a, lookup)) for a in node.args]
        return _FUNCTIONS[node.func.id](*arguments)
    raise ExpressionError(f"{ast.unparse(node)!r} is not part of the expression grammar")


def lookup_in(values: Mapping[str, Value]) -> Callable[[str], Value]:
    def lookup(name: str) -> Value:
        try:
            return values[name]
        except KeyError:
            raise ExpressionError(f"no parameter {name!r}") from None

    return lookup
