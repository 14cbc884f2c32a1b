"""The morai_msgs releases a bag may be recorded in, each seen through its typed view.

A bag's messages decode into the classes of the release it was recorded in, so what a
reader gets from a topic is that topic's type in any one of the releases: a union of
egosim.msgs.typed's types, whose differences (a field an older release names otherwise
or lacks) the type checker makes the reader handle.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Literal, Protocol, TypeVar, get_args

from egosim.msgs import get_profile

from .errors import UnsupportedReleaseError

if TYPE_CHECKING:
    from egosim.msgs.typed import morai_24_r2, morai_26_r1, morai_2021_08

    BagRelease = (
        morai_26_r1.ReleaseProfile | morai_24_r2.ReleaseProfile | morai_2021_08.ReleaseProfile
    )

M_co = TypeVar("M_co", covariant=True)

ReleaseName = Literal["26.r1", "24.r2", "2021.08"]
RELEASE_NAMES: tuple[ReleaseName, ...] = get_args(ReleaseName)
"""Every release egosim speaks (egosim.msgs.PROFILES), newest first."""


class Decoder(Protocol[M_co]):
    """What reading a bag needs of a message type: its messages from their bytes."""

    def deserialize(self, data: bytes | memoryview) -> M_co: ...


def bag_release(name: str) -> BagRelease:
    """The release `name`, typed; UnsupportedReleaseError for a release egosim lacks."""
    # One branch per literal, so each release comes back through its typed view.
    if name == "26.r1":
        return get_profile("26.r1")
    if name == "24.r2":
        return get_profile("24.r2")
    if name == "2021.08":
        return get_profile("2021.08")
    known = ", ".join(RELEASE_NAMES)
    raise UnsupportedReleaseError(f"unknown protocol profile {name!r} (known: {known})")
