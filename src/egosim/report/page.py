"""The drive report page: trajectory over the map, the ego's series, events on the time axis."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from matplotlib.figure import Figure

from egosim.evaluation import Infraction
from egosim.plots import (
    Block,
    FigureBlock,
    Panel,
    PlaceMark,
    Series,
    TableBlock,
    TextBlock,
    TimeMark,
    draw_map,
    draw_marks,
    draw_path,
    map_axes,
    points_view,
    series_figure,
)
from egosim.world.map import LaneMap

from .lane_analysis import LaneErrors, lane_errors, red_lights_run
from .recorded_drive import RecordedDrive

COLLISION = "collision"
CONTACT_AT_START = "contact_at_start"
RED_LIGHT = "red_light"
TRAJECTORY_MARGIN_M = 30.0
TRAJECTORY_MAX_PX = 1600
# The least y spans of the panels: a car on its lane's centre shows a flat line, not noise.
STEER_SPAN_RAD = 0.1
LATERAL_SPAN_M = 0.5
HEADING_SPAN_RAD = 0.1


@dataclass(frozen=True)
class DriveEvent:
    """A collision or a red light run: when, where, what (`label` short, `detail` full)."""

    time_s: float
    x: float
    y: float
    kind: str
    label: str
    detail: str


def drive_events(
    drive: RecordedDrive, lane_map: LaneMap, red_lights: list[Infraction]
) -> list[DriveEvent]:
    """Collisions, contacts under way when the recording began, and red lights run, by
    time."""
    events = [
        DriveEvent(
            c.time_s, c.x, c.y, COLLISION, f"hit {c.name}", f"with {c.name} (id {c.unique_id})"
        )
        for c in drive.collisions
    ]
    events += [
        DriveEvent(
            c.time_s,
            c.x,
            c.y,
            CONTACT_AT_START,
            f"touching {c.name}",
            f"already touching {c.name} (id {c.unique_id}) when the recording began",
        )
        for c in drive.contacts_at_start
    ]
    for run in red_lights:
        # An infraction at a stop line stands on the centre line of the lane it governs.
        heads = lane_map.lanes[lane_map.project(run.x, run.y).lane_id].traffic_light_ids
        label = f"red light {'/'.join(heads)}" if heads else "red light"
        events.append(DriveEvent(run.time_s, run.x, run.y, RED_LIGHT, label, run.detail))
    return sorted(events, key=lambda e: e.time_s)


def drive_report_blocks(drive: RecordedDrive, lane_map: LaneMap, map_note: str = "") -> list[Block]:
    """Summary, trajectory over `lane_map`, the time series and the event table."""
    errors = lane_errors(lane_map, drive)
    events = drive_events(drive, lane_map, red_lights_run(lane_map, drive, errors))
    return [
        TextBlock("Drive", _summary(drive, lane_map, errors, events, map_note)),
        FigureBlock(
            "Trajectory over the map",
            _trajectory_figure(drive, lane_map, events),
            "trajectory",
            caption="Circle: start, square: end; crosses: collisions (red), red lights "
            "run (orange) and contacts under way when the recording began. Metres in the map "
            "frame.",
        ),
        FigureBlock(
            "Speed, steering, pedals and lane errors",
            _series_figure(drive, errors, events),
            "series",
            caption="Lateral error: distance from the lane's centre line, left positive. "
            "Heading error: the ego's heading minus the lane's.",
        ),
        TableBlock(
            "Events",
            ("time (s)", "kind", "x (m)", "y (m)", "detail"),
            [(e.time_s, e.kind, e.x, e.y, e.detail) for e in events],
        ),
    ]


def _summary(
    drive: RecordedDrive,
    lane_map: LaneMap,
    errors: LaneErrors,
    events: list[DriveEvent],
    map_note: str,
) -> str:
    distance = float(np.sum(np.hypot(np.diff(drive.x), np.diff(drive.y))))
    duration = float(drive.times_s[-1] - drive.times_s[0]) if len(drive.times_s) else 0.0
    lateral = np.abs(errors.lateral_m)
    lines = [
        f"bag: {drive.path} (morai_msgs {drive.profile})",
        f"map: {lane_map.name}{f' ({map_note})' if map_note else ''}",
        f"ego samples: {len(drive.times_s)} over {duration:.2f} s; {distance:.1f} m driven",
        f"speed: max {float(np.max(drive.speed_mps)):.2f} m/s, "
        f"mean {float(np.mean(drive.speed_mps)):.2f} m/s",
        f"lateral error: max {float(np.max(lateral)):.2f} m, "
        f"RMS {float(np.sqrt(np.mean(lateral**2))):.2f} m",
        f"collisions: {sum(e.kind == COLLISION for e in events)}" + _under_way_note(events),
        f"red lights run: {sum(e.kind == RED_LIGHT for e in events)}"
        + ("" if drive.light_states else " (the bag holds no light status)"),
    ]
    return "\n".join(lines)


def _under_way_note(events: list[DriveEvent]) -> str:
    under_way = sum(e.kind == CONTACT_AT_START for e in events)
    if not under_way:
        return ""
    return f" ({under_way} more already under way when the recording began: not counted)"


def _trajectory_figure(drive: RecordedDrive, lane_map: LaneMap, events: list[DriveEvent]) -> Figure:
    figure, axes = map_axes(
        points_view(drive.xy, TRAJECTORY_MARGIN_M), max_px=TRAJECTORY_MAX_PX, dpi=120
    )
    draw_map(axes, lane_map)
    draw_path(axes, drive.xy, label="ego")
    draw_marks(axes, [PlaceMark(e.x, e.y, f"{e.time_s:.1f} s", e.kind) for e in events])
    axes.set_title(f"ego trajectory on map {lane_map.name}", fontsize=9)
    return figure


def _series_figure(drive: RecordedDrive, errors: LaneErrors, events: list[DriveEvent]) -> Figure:
    t = drive.times_s
    panels = [
        Panel("speed", "m/s", (Series("forward speed", t, drive.speed_mps),)),
        Panel(
            "steering", "rad", (Series("front wheels", t, drive.front_steer_rad),), STEER_SPAN_RAD
        ),
        Panel(
            "pedals",
            "0..1",
            (Series("accelerator", t, drive.accel_pedal), Series("brake", t, drive.brake_pedal)),
        ),
        Panel("lateral error", "m", (Series("from centre", t, errors.lateral_m),), LATERAL_SPAN_M),
        Panel(
            "heading error",
            "rad",
            (Series("heading error", t, errors.heading_error_rad),),
            HEADING_SPAN_RAD,
        ),
    ]
    marks = [TimeMark(e.time_s, e.label, e.kind) for e in events]
    return series_figure(panels, marks)
