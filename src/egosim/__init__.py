"""egosim: a headless driving simulator that speaks the MORAI SIM ROS 1 protocol."""

__version__ = "0.1.0"
