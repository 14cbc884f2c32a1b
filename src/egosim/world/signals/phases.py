"""Phase programs: the fixed-time sequence of aspects an intersection cycles through.

A program serves each approach group of an intersection in turn (see build_program)
and every phase ends in yellow then all-red clearance, so two conflicting movements
never hold a go aspect at once.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from egosim.world.map.light_type import LightType
from egosim.world.signals.aspects import (
    GREEN,
    GREEN_LEFT,
    OFF,
    RED,
    YELLOW,
    go_lamps,
    has_green,
    has_left_arrow,
)


@dataclass(frozen=True)
class PhaseTiming:
    """Durations of the steps of a phase program, s."""

    green_s: float = 25.0
    """Through movement (with the left turn, for a head alone in its group)."""
    left_s: float = 10.0
    """Protected left-arrow phase of a group of several heads; a left-arrow-only head
    alone in its group."""
    yellow_s: float = 3.0
    all_red_s: float = 2.0
    flash_s: float = 0.5
    """Half period of a flashing (type 100) head: this long lit, this long dark."""

    def __post_init__(self) -> None:
        for name in ("green_s", "left_s", "yellow_s", "all_red_s", "flash_s"):
            if not getattr(self, name) > 0.0:
                raise ValueError(f"{name} must be > 0")


@dataclass(frozen=True)
class Phase:
    """One step of a program: what every light of the intersection shows, for how long."""

    name: str
    duration_s: float
    aspects: tuple[int, ...]
    """Aspect per light, in the controller's light order."""


def build_program(
    light_ids: Sequence[str],
    light_types: Mapping[str, int],
    approach_groups: Sequence[Sequence[str]],
    timing: PhaseTiming,
) -> tuple[Phase, ...]:
    """The fixed-time program for one intersection.

    Each approach group in turn gets:
    - one head alone: its go lamps (green, and the left arrow if it has one: nothing
      opposes its turn while it alone goes), yellow, all-red;
    - several heads, none with a left arrow: green, yellow, all-red;
    - several heads, some with a left arrow: a protected left phase (the arrow, with the
      red on heads that have one), yellow, all-red, then green for the heads that have
      one (left turns wait), yellow, all-red.
    Flashing heads (type 100) show yellow in every phase; an intersection of flashing
    heads only has two phases, lit and dark, of `flash_s` each.
    """
    ids = tuple(light_ids)
    flashing = {i for i in ids if light_types[i] == LightType.FLASHING_YELLOW}
    if flashing == set(ids):
        return (
            Phase("flash on", timing.flash_s, tuple(YELLOW for _ in ids)),
            Phase("flash off", timing.flash_s, tuple(OFF for _ in ids)),
        )

    def phase(name: str, duration: float, lit: Mapping[str, int]) -> Phase:
        aspects = tuple(YELLOW if i in flashing else lit.get(i, RED) for i in ids)
        return Phase(name, duration, aspects)

    def serve(name: str, go: Mapping[str, int]) -> list[Phase]:
        return [
            phase(f"{name} go", timing.green_s if _bits(go) & GREEN else timing.left_s, go),
            phase(f"{name} yellow", timing.yellow_s, dict.fromkeys(go, YELLOW)),
            phase(f"{name} all red", timing.all_red_s, {}),
        ]

    program: list[Phase] = []
    for group in approach_groups:
        heads = [i for i in group if i not in flashing]
        if not heads:
            continue
        arrows = [i for i in heads if has_left_arrow(light_types[i])]
        greens = [i for i in heads if has_green(light_types[i])]
        if len(heads) == 1:
            head = heads[0]
            program += serve(head, {head: go_lamps(light_types[head])})
        elif arrows:
            left = {i: GREEN_LEFT | (RED if has_green(light_types[i]) else 0) for i in arrows}
            program += serve(f"{'+'.join(arrows)} left", left)
            if greens:
                program += serve("+".join(greens), dict.fromkeys(greens, GREEN))
        else:
            program += serve("+".join(heads), dict.fromkeys(heads, GREEN))
    return tuple(program)


def _bits(aspects: Mapping[str, int]) -> int:
    combined = 0
    for aspect in aspects.values():
        combined |= aspect
    return combined
