import json
import logging
import shutil
from pathlib import Path

import pytest

from egosim.maps import MapLoadError, load_map, read_map
from egosim.world.map import BUILTIN_MAP_NAMES
from tests.world.map.mgeo.sample_mgeo import mgeo_files

DATA = Path(__file__).parent / "data" / "maps"


@pytest.fixture
def mgeo_folder(tmp_path: Path) -> Path:
    folder = tmp_path / "track"
    folder.mkdir()
    for name, content in mgeo_files().items():
        (folder / name).write_text(json.dumps(content, indent=1))
    return folder


@pytest.mark.parametrize("name", BUILTIN_MAP_NAMES)
def test_builtin_names_give_builtin_maps(name):
    assert load_map(name).name == name


def test_a_folder_loads_as_mgeo(mgeo_folder):
    lane_map = load_map(str(mgeo_folder))
    assert lane_map.name == "track"
    assert len(lane_map.lanes) == 23
    assert lane_map.intersections[1].approach_groups == (("TL_N", "TL_S"), ("TL_E", "TL_W"))


def test_other_json_files_of_the_folder_are_reported(mgeo_folder, caplog):
    (mgeo_folder / "crosswalk_set.json").write_text("[]")
    (mgeo_folder / "readme.txt").write_text("not a map file")
    assert "crosswalk_set.json not read" in read_map(str(mgeo_folder)).notes
    with caplog.at_level(logging.WARNING, logger="egosim.maps"):
        load_map(str(mgeo_folder))
    assert any("crosswalk_set.json not read" in r.getMessage() for r in caplog.records)


def test_an_xodr_file_loads_as_opendrive():
    lane_map = load_map(str(DATA / "junction.xodr"))
    assert lane_map.name == "junction"
    assert lane_map.intersections[100].approach_groups == (("TL2", "TL4"), ("TL1", "TL3"))


def test_a_byte_order_mark_is_accepted(mgeo_folder):
    path = mgeo_folder / "global_info.json"
    path.write_bytes(b"\xef\xbb\xbf" + path.read_bytes())
    assert load_map(str(mgeo_folder)).georef.utm_zone == 52


def one_line_error(path: str) -> str:
    with pytest.raises(MapLoadError) as caught:
        load_map(path)
    message = str(caught.value)
    assert "\n" not in message
    return message


def test_broken_json_names_file_line_and_column(mgeo_folder):
    (mgeo_folder / "link_set.json").write_text('[\n  {"idx": "A",\n  "points": [1, 2,]}\n]')
    message = one_line_error(str(mgeo_folder))
    assert message.startswith(f"{mgeo_folder / 'link_set.json'}: line 3 column")


def test_malformed_mgeo_record_names_file_and_record(mgeo_folder):
    links = json.loads((mgeo_folder / "link_set.json").read_text())
    links[3]["max_speed"] = "fast"
    (mgeo_folder / "link_set.json").write_text(json.dumps(links))
    message = one_line_error(str(mgeo_folder))
    assert message == (
        f"{mgeo_folder / 'link_set.json'}: record #3 (idx {links[3]['idx']!r}): "
        "max_speed must be a number, got 'fast'"
    )


def test_missing_mgeo_file_is_named(mgeo_folder):
    (mgeo_folder / "global_info.json").unlink()
    assert one_line_error(str(mgeo_folder)) == (
        f"{mgeo_folder / 'global_info.json'}: file: is missing"
    )


def test_malformed_xodr_names_file_and_element(tmp_path):
    path = tmp_path / "bad.xodr"
    shutil.copy(DATA / "junction.xodr", path)
    path.write_text(path.read_text().replace('curvature="0.1"', 'curvature="tight"', 1))
    message = one_line_error(str(path))
    assert message.startswith(f"{path}: road id='14' geometry #0 arc: ")
    assert message.endswith("attribute curvature='tight' is not a number")


def test_unknown_names_and_formats_are_refused(tmp_path):
    assert "no such file or folder, nor a built-in map (town" in one_line_error("downtown")
    other = tmp_path / "map.osm"
    other.write_text("<osm/>")
    assert one_line_error(str(other)) == f"{other}: not an MGeo folder or an OpenDRIVE .xodr file"
