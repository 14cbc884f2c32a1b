"""Every light and intersection controller of a map, with the overrides clients set."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from egosim.world.map import LaneMap
from egosim.world.signals.aspects import OFF, can_show
from egosim.world.signals.controller import IntersectionController, IntersectionStatus
from egosim.world.signals.errors import (
    UnknownIntersectionError,
    UnknownLightError,
    UnsupportedAspectError,
)
from egosim.world.signals.lane_signals import LaneSignals
from egosim.world.signals.phases import PhaseTiming, build_program


@dataclass(frozen=True)
class IntersectionProgram:
    """How one intersection runs: its timing and where its program starts."""

    timing: PhaseTiming = field(default_factory=PhaseTiming)
    initial_phase: int = 0
    initial_elapsed_s: float = 0.0


@dataclass(frozen=True)
class LightState:
    """GetTrafficLightStatus semantics for one light."""

    light_id: str
    light_type: int
    aspect: int
    overridden: bool


class TrafficSignals:
    """The map's lights, driven by one controller per intersection.

    Override semantics: set_light holds a light's aspect (OFF switches it dark) until
    release_light, until control_intersection on its intersection, or until configure
    (a scenario load). A light whose site names no intersection of the map shows OFF
    unless overridden.
    """

    def __init__(
        self,
        lane_map: LaneMap,
        programs: Mapping[int, IntersectionProgram] | None = None,
        default: IntersectionProgram | None = None,
    ) -> None:
        self._map = lane_map
        self.light_ids: tuple[str, ...] = tuple(lane_map.traffic_lights)
        self._light_index = {light_id: k for k, light_id in enumerate(self.light_ids)}
        self.light_types = np.array(
            [lane_map.traffic_lights[i].light_type for i in self.light_ids], dtype=np.int64
        )
        self.lane_signals = LaneSignals(lane_map, self.light_ids)
        """The signal each lane's drivers obey (its heads read together)."""
        self.controllers: dict[int, IntersectionController] = {}
        self._overrides: dict[str, int] = {}
        self._aspects = np.full(len(self.light_ids), OFF, dtype=np.int64)
        self._signal_aspects = self._aspects
        self.changes = 0
        """How many times an aspect may have changed: what a reader works out from the
        aspects holds while this stays the same."""
        self.configure(programs, default)

    def configure(
        self,
        programs: Mapping[int, IntersectionProgram] | None = None,
        default: IntersectionProgram | None = None,
    ) -> None:
        """Rebuild every controller (per-intersection programs over `default`); drop overrides."""
        programs = programs or {}
        unknown = sorted(set(programs) - set(self._map.intersections))
        if unknown:
            raise UnknownIntersectionError(f"no intersections {unknown} in map {self._map.name}")
        default = default or IntersectionProgram()
        types = {i: self._map.traffic_lights[i].light_type for i in self.light_ids}
        self.controllers = {}
        for site in self._map.intersections.values():
            if not site.light_ids:
                continue
            program = programs.get(site.id, default)
            phases = build_program(site.light_ids, types, site.approach_groups, program.timing)
            self.controllers[site.id] = IntersectionController(
                site.id,
                site.light_ids,
                phases,
                program.initial_phase,
                program.initial_elapsed_s,
            )
        self._overrides.clear()
        self._refresh()

    def step(self, dt: float) -> None:
        # Phases last seconds: most steps change no aspect and need no refresh.
        changed = False
        for controller in self.controllers.values():
            changed |= controller.step(dt)
        if changed:
            self._refresh()

    def _refresh(self) -> None:
        for controller in self.controllers.values():
            for light_id, aspect in zip(
                controller.light_ids, controller.phase.aspects, strict=True
            ):
                self._aspects[self._light_index[light_id]] = aspect
        for light_id, aspect in self._overrides.items():
            self._aspects[self._light_index[light_id]] = aspect
        self._update_signals()

    def _update_signals(self) -> None:
        # Kept between changes: agents read the signals every step, aspects change seldom.
        self._signal_aspects = self.lane_signals.aspects(self._aspects)
        self.changes += 1

    def aspects(self) -> npt.NDArray[np.int64]:
        """Aspect of every light, in `light_ids` order (read-only view)."""
        view: npt.NDArray[np.int64] = self._aspects.view()
        view.flags.writeable = False
        return view

    def signal_aspects(self) -> npt.NDArray[np.int64]:
        """Aspect of every signal of `lane_signals`: the lights' own, then those of the
        sets of heads governing a lane together (read-only view)."""
        view: npt.NDArray[np.int64] = self._signal_aspects.view()
        view.flags.writeable = False
        return view

    def light_index(self, light_id: str) -> int:
        try:
            return self._light_index[light_id]
        except KeyError:
            raise UnknownLightError(f"no traffic light {light_id!r}") from None

    def light(self, light_id: str) -> LightState:
        k = self.light_index(light_id)
        return LightState(
            light_id,
            int(self.light_types[k]),
            int(self._aspects[k]),
            light_id in self._overrides,
        )

    def set_light(self, light_id: str, aspect: int) -> None:
        """SetTrafficLight: hold `aspect` on the light (see the class docstring)."""
        k = self.light_index(light_id)
        if not can_show(int(self.light_types[k]), aspect):
            raise UnsupportedAspectError(
                f"light {light_id} (type {self.light_types[k]}) cannot show {aspect}"
            )
        self._overrides[light_id] = aspect
        self._aspects[k] = aspect
        self._update_signals()

    def release_light(self, light_id: str) -> None:
        """Hand the light back to its intersection's program."""
        self.light_index(light_id)
        self._overrides.pop(light_id, None)
        self._refresh()

    def controller(self, intersection_id: int) -> IntersectionController:
        try:
            return self.controllers[intersection_id]
        except KeyError:
            raise UnknownIntersectionError(
                f"no signalised intersection {intersection_id}"
            ) from None

    def control_intersection(
        self, intersection_id: int, phase_index: int, elapsed_s: float
    ) -> None:
        """IntersectionControl: jump to a phase and time in it; releases its lights' overrides."""
        controller = self.controller(intersection_id)
        controller.jump(phase_index, elapsed_s)
        for light_id in controller.light_ids:
            self._overrides.pop(light_id, None)
        self._refresh()

    def intersection_status(self, intersection_id: int) -> IntersectionStatus:
        return self.controller(intersection_id).status()

    def intersection_statuses(self) -> list[IntersectionStatus]:
        return [c.status() for c in self.controllers.values()]
