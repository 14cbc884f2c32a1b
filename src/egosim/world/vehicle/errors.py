"""Exceptions of the vehicle package."""

from __future__ import annotations


class VehicleError(Exception):
    """Base class of every error raised by egosim.world.vehicle."""


class UnknownVehicleModelError(VehicleError, LookupError):
    """A vehicle model name that is not in the catalogue."""

    def __init__(self, name: str, known: list[str]) -> None:
        super().__init__(f"unknown vehicle model {name!r}; known models: {', '.join(known)}")
        self.name = name
        self.known = known
