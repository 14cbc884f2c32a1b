"""What `egosim run` was asked to do."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from ..bridge.clock import ClockMode
from ..bridge.protocol.codes import ControlMode


@dataclass(frozen=True)
class RunOptions:
    map: str | None = None
    """A map name or path; None: the scenario's map, else the town."""
    scenario: Path | None = None
    network: Path | None = None
    clock: ClockMode = ClockMode.REAL
    rtf: float = 1.0
    duration: float | None = None  # seconds of simulation time, None: until stopped
    record: Path | None = None
    protocol: str = "26.r1"
    log_level: str = "INFO"
    physics_rate_hz: float = 100.0
    data_roots: tuple[Path, ...] = field(default_factory=tuple)
    ros_argv: tuple[str, ...] = ()  # __name:=, __ns:=, from:=to ...
    ctrl_mode: ControlMode = ControlMode.EXTERNAL
    """The main ego's control mode at start: external (its stack drives) or auto."""
    scenario_parameters: tuple[tuple[str, str], ...] = ()
    """--param NAME=VALUE: values of an OpenSCENARIO file's declared parameters."""
    keep_running: bool = False
    """Keep running after the OpenSCENARIO scenario's storyboard has ended."""
    camera_scene_at_first_frame: bool = False
    """Build the map's camera scene when a camera first renders, not before the run
    starts (the first frame then takes that long: a batch case, which seldom renders)."""

    @property
    def physics_dt(self) -> float:
        return 1.0 / self.physics_rate_hz
