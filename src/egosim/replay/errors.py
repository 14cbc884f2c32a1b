"""Errors of the replay package."""


class ReplayError(Exception):
    """Base class of every replay-package error."""


class RecorderError(ReplayError):
    """A bag cannot be created, or its writer failed while recording."""


class BagError(ReplayError):
    """A bag file is not a readable ROS 1 (v2.0) bag, even after repair."""


class BagInUseError(BagError):
    """The bag is still being recorded by this process; it cannot be repaired or replayed."""


class UnsupportedReleaseError(BagError):
    """The bag's connections carry md5sums of no morai_msgs release egosim ships."""


class MissingTopicsError(BagError):
    """The bag holds none of the topics a replay needs."""
