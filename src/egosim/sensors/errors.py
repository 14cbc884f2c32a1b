"""Exceptions raised by the sensor models."""

from __future__ import annotations


class SensorError(Exception):
    """Base class of the sensor models' errors."""


class SensorConfigError(SensorError, ValueError):
    """A sensor was configured with values it cannot model."""


class MissingRandomGeneratorError(SensorError, ValueError):
    """A noisy sensor was asked to measure without a random generator."""


class RendererUnavailableError(SensorError):
    """No camera renderer can run here (no OpenGL driver...); the message says why."""
