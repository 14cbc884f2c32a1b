"""examples/egosim.rviz shows what egosim publishes, under the names and types it uses."""

from __future__ import annotations

from pathlib import Path

import yaml

from egosim.bridge.protocol.table import ROWS_BY_KEY

LAYOUT = Path(__file__).parents[2] / "examples" / "egosim.rviz"
# RViz display classes and the message types they read.
DISPLAY_TYPES = {
    "rviz/MarkerArray": ("Marker Topic", "visualization_msgs/MarkerArray"),
    "rviz/PointCloud2": ("Topic", "sensor_msgs/PointCloud2"),
}


def test_the_layout_shows_the_markers_lidar_tf_and_camera() -> None:
    layout = yaml.safe_load(LAYOUT.read_text())
    manager = layout["Visualization Manager"]
    assert manager["Global Options"]["Fixed Frame"] == "map"
    displays = {d["Class"]: d for d in manager["Displays"]}
    published = {row.name: row.type_name for row in ROWS_BY_KEY.values()}
    for display_class, (field, type_name) in DISPLAY_TYPES.items():
        topic = displays[display_class][field]
        assert published[topic] == type_name, display_class
    assert displays["rviz/MarkerArray"]["Marker Topic"] == ROWS_BY_KEY["markers"].name
    assert displays["rviz/PointCloud2"]["Topic"] == ROWS_BY_KEY["lidar"].name
    assert "rviz/TF" in displays  # the ego's base_link and sensor frames from /tf
    camera = displays["rviz/Image"]
    assert (camera["Image Topic"], camera["Transport Hint"]) == ("/image_jpeg", "compressed")
    assert manager["Views"]["Current"]["Target Frame"] == "base_link"
