"""Drive reports from bags egosim recorded (`egosim report BAG -o report.html`).

    drive = read_drive("run.bag")                      # RecordedDrive: SI arrays + events
    written = write_drive_report(drive, load_map("town"), Path("report.html"))

`recorded_drive` reads the bag (rosbags, through the replay package's timeline);
`lane_analysis` sets the drive against its map (lane errors, red lights run, which
built-in map it was on); `page` lays out the page with egosim.plots.
"""

from __future__ import annotations

from pathlib import Path

from egosim.plots import write_report
from egosim.world.map import LaneMap

from .lane_analysis import LaneErrors, best_fitting_map, lane_errors, red_lights_run
from .page import DriveEvent, drive_events, drive_report_blocks
from .recorded_drive import LightState, RecordedCollision, RecordedDrive, read_drive


def write_drive_report(
    drive: RecordedDrive, lane_map: LaneMap, path: Path, map_note: str = ""
) -> list[Path]:
    """Write the report page at `path` and its PNGs beside it; returns the files written."""
    blocks = drive_report_blocks(drive, lane_map, map_note)
    return write_report(path, f"Drive report: {drive.path.name}", blocks)


__all__ = [
    "DriveEvent",
    "LaneErrors",
    "LightState",
    "RecordedCollision",
    "RecordedDrive",
    "best_fitting_map",
    "drive_events",
    "drive_report_blocks",
    "lane_errors",
    "read_drive",
    "red_lights_run",
    "write_drive_report",
]
