"""Time-series figures: the drawn lines are the data given, events cross every panel."""

from __future__ import annotations

import numpy as np
import pytest

from egosim.plots import Panel, Series, TimeMark, kind_color, series_figure


def test_each_panel_draws_its_series_and_every_mark() -> None:
    t = np.linspace(0.0, 10.0, 101)
    speed = 2.0 * t
    panels = [
        Panel("speed", "m/s", (Series("speed", t, speed),)),
        Panel("pedals", "0..1", (Series("accel", t, t / 10), Series("brake", t, 1 - t / 10))),
    ]
    marks = [TimeMark(3.5, "hit NPC 3", "collision"), TimeMark(7.0, "TL6_N red", "red_light")]
    figure = series_figure(panels, marks, title="drive")
    speed_axes, pedal_axes = figure.axes
    (speed_line, *_speed_marks) = speed_axes.get_lines()
    assert np.array_equal(speed_line.get_xdata(), t)
    assert np.array_equal(speed_line.get_ydata(), speed)
    assert [line.get_label() for line in pedal_axes.get_lines()[:2]] == ["accel", "brake"]
    for axes in (speed_axes, pedal_axes):
        verticals = axes.get_lines()[len(axes.get_lines()) - 2 :]
        assert [line.get_xdata()[0] for line in verticals] == [3.5, 7.0]
        assert [line.get_color() for line in verticals] == [
            kind_color("collision"),
            kind_color("red_light"),
        ]
    assert {t.get_text() for t in speed_axes.texts} == {"hit NPC 3", "TL6_N red"}
    assert speed_axes.get_shared_x_axes().joined(speed_axes, pedal_axes)


def test_mismatched_series_is_a_clear_error() -> None:
    with pytest.raises(ValueError, match="'speed'"):
        series_figure([Panel("speed", "m/s", (Series("speed", [0, 1, 2], [1, 2]),))])


def test_kind_colours_are_stable_and_collisions_share_one() -> None:
    assert kind_color("collision_vehicle") == kind_color("collision_pedestrian")
    assert kind_color("collision") != kind_color("red_light")
    assert kind_color("lane_departure") == kind_color("lane_departure")
