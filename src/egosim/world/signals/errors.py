"""Exceptions raised by the signals package."""


class SignalError(Exception):
    """Base class for traffic light and intersection errors."""


class UnknownLightError(SignalError, KeyError):
    """A trafficLightIndex that names no light of the map."""


class UnknownIntersectionError(SignalError, KeyError):
    """An intersection index that names no signalised intersection of the map."""


class UnsupportedAspectError(SignalError, ValueError):
    """An aspect the light's head type has no lamps for."""


class UnknownPhaseError(SignalError, IndexError):
    """A phase index outside an intersection's program."""

    def __init__(self, intersection_id: int, phase_index: int, phase_count: int) -> None:
        self.intersection_id = intersection_id
        super().__init__(
            f"intersection {intersection_id} has phases 0..{phase_count - 1}, not {phase_index}"
        )
