"""The map picture: every road lane and light labelled where it is, legibly, at scale."""

from __future__ import annotations

import io
import itertools

import numpy as np
import pytest
from PIL import Image

from egosim.plots import figure_png, light_color, map_axes, map_figure, map_view, points_view
from egosim.plots.map_figure import PlaceMark, draw_map, draw_marks, draw_path, nice_length
from egosim.world.map import build_builtin_map


@pytest.fixture(scope="module")
def town():
    return build_builtin_map("town")


@pytest.fixture(scope="module")
def town_picture(town):
    return map_figure(town)


def _label_texts(figure):
    (axes,) = figure.axes
    return axes, [t for t in axes.texts if t.get_text().strip("←→ ")]


def test_every_road_lane_and_light_of_the_town_is_labelled(town, town_picture) -> None:
    _, drawn = town_picture
    road_lanes = {lane.id for lane in town.lanes.values() if not lane.is_junction}
    assert set(drawn.lanes) == road_lanes
    assert len(drawn.lanes) == 224
    assert set(drawn.lights) == set(town.traffic_lights)


def test_lane_labels_sit_on_their_lane_and_point_its_way(town, town_picture) -> None:
    figure, _ = town_picture
    _axes, texts = _label_texts(figure)
    checked = 0
    for text in texts:
        label = text.get_text()
        lane_id = label.strip("←→ ")
        if lane_id not in town.lanes:
            continue
        x, y = text.get_position()
        lane = town.lanes[lane_id]
        projection = town.project(x, y, town.project(x, y).heading)
        distance = np.min(np.hypot(*(lane.centerline[:, :2] - (x, y)).T))
        assert projection.lane_id == lane_id or distance < 0.5, label
        # The arrow points along the lane: text direction (+ for →, - for ←) vs heading.
        heading = projection.heading if projection.lane_id == lane_id else None
        if heading is not None:
            rotation = np.radians(text.get_rotation())
            along = np.cos(rotation - heading)
            assert (along > 0.5) if label.endswith("→") else (along < -0.5), label
        checked += 1
    assert checked == 224


def test_labels_never_overlap(town_picture) -> None:
    figure, _ = town_picture
    _axes, texts = _label_texts(figure)
    renderer = figure.canvas.get_renderer()
    boxes = [t.get_window_extent(renderer) for t in texts]
    assert len(boxes) == 224 + 112
    overlapping = [
        (a.get_text(), b.get_text())
        for (a, box_a), (b, box_b) in itertools.combinations(zip(texts, boxes, strict=True), 2)
        if box_a.overlaps(box_b)
    ]
    assert overlapping == []


def test_png_decodes_at_the_maps_proportions(town) -> None:
    figure, _ = map_figure(town, max_px=800)
    image = Image.open(io.BytesIO(figure_png(figure)))
    image.verify()
    width, height = Image.open(io.BytesIO(figure_png(figure))).size
    (axes,) = figure.axes
    box = axes.get_window_extent()
    # The town is a square: its axes are square in pixels, 800 px a side.
    assert box.width == pytest.approx(800, abs=2)
    assert box.height == pytest.approx(800, abs=2)
    assert width > 800 and height > 800


def test_a_light_is_drawn_in_its_aspect_colour(town) -> None:
    light = town.traffic_lights["TL6_N"]
    figure, axes = map_axes(points_view([light.position[:2]], margin_m=10), max_px=400)
    draw_map(axes, town, light_aspects={"TL6_N": 1})
    figure.canvas.draw()
    px, py = axes.transData.transform(light.position[:2])
    rgba = np.asarray(figure.canvas.buffer_rgba())
    row = rgba.shape[0] - round(py)
    pixel = rgba[row, round(px), :3]
    red = np.array([int(light_color(1)[i : i + 2], 16) for i in (1, 3, 5)])
    assert np.abs(pixel.astype(int) - red).max() < 20


def test_a_view_of_a_trajectory_labels_only_what_it_shows(town) -> None:
    path = np.column_stack((np.linspace(-60, 60, 50), np.full(50, -91.75)))
    _figure, axes = map_axes(points_view(path, margin_m=20), max_px=600)
    drawn = draw_map(axes, town)
    draw_path(axes, path, label="ego")
    draw_marks(axes, [PlaceMark(0.0, -91.75, "collision with NPC 3", "collision")])
    assert "R5_E_1" in drawn.lanes
    assert all(lane.startswith(("R5_", "R17_", "R20_", "R16_", "R19_")) for lane in drawn.lanes)
    xmin, xmax = axes.get_xlim()
    assert xmin < -60 and xmax > 60 and xmax - xmin < 300


@pytest.mark.parametrize(
    ("span", "length"), [(862.0, 100.0), (1060.0, 200.0), (180.0, 20.0), (60.0, 10.0), (9.0, 1.0)]
)
def test_scale_bar_length_is_a_round_fifth_of_the_view(span: float, length: float) -> None:
    assert nice_length(span) == length


@pytest.mark.parametrize("name", ["straight", "loop"])
def test_every_lane_of_the_small_maps_is_labelled(name: str) -> None:
    lane_map = build_builtin_map(name)
    figure, drawn = map_figure(lane_map)
    assert set(drawn.lanes) == set(lane_map.lanes)
    xmin, _ymin, xmax, _ymax = map_view(lane_map)
    (axes,) = figure.axes
    assert axes.get_xlim()[0] < xmin and axes.get_xlim()[1] > xmax
