"""One concrete case: everything a worker needs to run it, as plain picklable data."""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any

from egosim.batch.sweep import Value, format_value


@dataclass(frozen=True)
class StackSpec:
    command: str
    """Shell command; {suite_dir}, {case_dir}, {case} and parameters are replaced."""
    env: dict[str, str] = field(default_factory=dict)
    connect_timeout_s: float = 30.0


@dataclass(frozen=True)
class CaseSpec:
    name: str
    """Stable: the case's name and its parameters, `lap[seed=1,speed=20]`."""
    scenario: dict[str, Any]
    """The scenario data with the case's parameters applied."""
    scenario_file: str
    parameters: dict[str, Value]
    stack: StackSpec
    suite_dir: str
    map: str
    """egosim run --map: a built-in map's name or a path."""
    route: dict[str, Any] | None = None
    """{"waypoints": [[x, y], ...]} or {"lanes": [...]}, optionally with "first_m"."""
    clock: str = "sim"
    rtf: float = 0.0
    time_limit_s: float = 60.0
    wall_limit_s: float = 720.0
    criteria: tuple[str, ...] = ()
    scoring: dict[str, Any] = field(default_factory=dict)
    bags: str = "all"
    """Which cases keep their bag: "all", "failed" (those that did not pass), "none"."""
    openscenario: str = ""
    """An OpenSCENARIO case's .xosc file (then `scenario` is empty)."""
    scenario_parameters: dict[str, str] = field(default_factory=dict)
    """Values of the OpenSCENARIO file's parameters for this case."""

    def as_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> CaseSpec:
        fields = dict(data)
        fields["stack"] = StackSpec(**fields["stack"])
        fields["criteria"] = tuple(fields["criteria"])
        return cls(**fields)

    def placeholders(self, case_dir: str) -> dict[str, str]:
        """What {name} stands for in the stack's command and environment."""
        values = {k: format_value(v) for k, v in self.parameters.items()}
        return {**values, "suite_dir": self.suite_dir, "case_dir": case_dir, "case": self.name}
