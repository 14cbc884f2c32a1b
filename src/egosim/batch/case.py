"""One concrete case: everything a worker needs to run it, as plain picklable data."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from typing import TypedDict, cast

from egosim.batch.sweep import Value, format_value
from egosim.json_value import JsonObject

DEFAULT_TIME_LIMIT_S = 60.0
"""Simulated time a case may take when its suite says nothing."""


@dataclass(frozen=True)
class StackSpec:
    command: str
    """Shell command; {suite_dir}, {case_dir}, {case} and parameters are replaced."""
    env: dict[str, str] = field(default_factory=dict)
    connect_timeout_s: float = 30.0


class StackFields(TypedDict):
    """A StackSpec as plain data."""

    command: str
    env: dict[str, str]
    connect_timeout_s: float


class CaseFields(TypedDict):
    """A CaseSpec as plain data (what a case's folder keeps as JSON)."""

    name: str
    scenario: JsonObject
    scenario_file: str
    parameters: dict[str, Value]
    stack: StackFields
    suite_dir: str
    map: str
    route: JsonObject | None
    clock: str
    rtf: float
    time_limit_s: float
    wall_limit_s: float
    criteria: Sequence[str]
    scoring: JsonObject
    bags: str
    openscenario: str
    scenario_parameters: dict[str, str]


@dataclass(frozen=True)
class CaseSpec:
    name: str
    """Stable: the case's name and its parameters, `lap[seed=1,speed=20]`."""
    scenario: JsonObject
    """The scenario data with the case's parameters applied."""
    scenario_file: str
    parameters: dict[str, Value]
    stack: StackSpec
    suite_dir: str
    map: str
    """egosim run --map: a built-in map's name or a path."""
    route: JsonObject | None = None
    """{"waypoints": [[x, y], ...]} or {"lanes": [...]}, optionally with "first_m"."""
    clock: str = "sim"
    rtf: float = 0.0
    time_limit_s: float = DEFAULT_TIME_LIMIT_S
    wall_limit_s: float = 720.0
    criteria: tuple[str, ...] = ()
    scoring: JsonObject = field(default_factory=dict)
    bags: str = "all"
    """Which cases keep their bag: "all", "failed" (those that did not pass), "none"."""
    openscenario: str = ""
    """An OpenSCENARIO case's .xosc file (then `scenario` is empty)."""
    scenario_parameters: dict[str, str] = field(default_factory=dict)
    """Values of the OpenSCENARIO file's parameters for this case."""

    def as_dict(self) -> CaseFields:
        # asdict turns the stack into the dict of its fields, as CaseFields has it.
        return cast(CaseFields, asdict(self))

    @classmethod
    def from_dict(cls, data: CaseFields) -> CaseSpec:
        return cls(
            name=data["name"],
            scenario=data["scenario"],
            scenario_file=data["scenario_file"],
            parameters=data["parameters"],
            stack=StackSpec(**data["stack"]),
            suite_dir=data["suite_dir"],
            map=data["map"],
            route=data["route"],
            clock=data["clock"],
            rtf=data["rtf"],
            time_limit_s=data["time_limit_s"],
            wall_limit_s=data["wall_limit_s"],
            criteria=tuple(data["criteria"]),
            scoring=data["scoring"],
            bags=data["bags"],
            openscenario=data["openscenario"],
            scenario_parameters=data["scenario_parameters"],
        )

    def placeholders(self, case_dir: str) -> dict[str, str]:
        """What {name} stands for in the stack's command and environment."""
        values = {k: format_value(v) for k, v in self.parameters.items()}
        return {**values, "suite_dir": self.suite_dir, "case_dir": case_dir, "case": self.name}
