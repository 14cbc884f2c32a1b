"""The live web view: serves a page on loopback, streams world snapshots to it, and
hands the page's controls to the simulation loop's inbox like any other command.

Public API:
    live_view(ViewOptions) -> Attach     what `egosim run` attaches to the loop
    ViewOptions, DEFAULT_HOST, DEFAULT_PORT
    snapshot.map_snapshot, snapshot.capture_frame, snapshot.encode   world -> JSON
    messages: the shapes of the map, frames, history and replies the page gets
"""

from .attach import DEFAULT_HOST, DEFAULT_PORT, ViewOptions, live_view

__all__ = ["DEFAULT_HOST", "DEFAULT_PORT", "ViewOptions", "live_view"]
