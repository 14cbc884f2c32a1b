"""`egosim map`: counts and ids with positions that are the loaded map's, and its picture."""

from __future__ import annotations

import io
import math
import re
import subprocess
import sys
from pathlib import Path

import pytest
from PIL import Image

from egosim.cli import main
from egosim.maps import load_map, map_names

DATA_MAPS = Path(__file__).parents[1] / "data" / "maps"
DOCS_MAPS = Path(__file__).parents[2] / "docs" / "maps"


def run_map(capsys: pytest.CaptureFixture[str], *args: str) -> str:
    assert main(["map", *args]) == 0
    return capsys.readouterr().out


def table(out: str, first_header: str) -> dict[str, dict[str, str]]:
    """The rows of the table whose header starts with `first_header`, by id."""
    lines = out.splitlines()
    start = next(i for i, line in enumerate(lines) if line.split()[:1] == [first_header])
    header = lines[start].split()
    rows: dict[str, dict[str, str]] = {}
    for line in lines[start + 1 :]:
        if not line.strip():
            break
        cells = line.split()
        rows[cells[0]] = dict(zip(header, cells, strict=True))
    return rows


def summary(out: str) -> dict[str, str]:
    return dict(
        line.split(": ", 1) for line in out.splitlines()[:8] if re.match(r"^[a-z ]+: ", line)
    )


@pytest.mark.parametrize("name", ["town", "straight", "loop", str(DATA_MAPS / "junction.xodr")])
def test_counts_are_the_loaded_maps(capsys: pytest.CaptureFixture[str], name: str) -> None:
    lane_map = load_map(name)
    facts = summary(run_map(capsys, name))
    lanes = list(lane_map.lanes.values())
    connectors = sum(lane.is_junction for lane in lanes)
    assert facts["map"] == lane_map.name
    assert facts["lanes"].startswith(
        f"{len(lanes)} ({len(lanes) - connectors} road lanes, {connectors} junction connectors"
    )
    assert facts["intersections"] == f"{len(lane_map.intersections)} signalised"
    assert facts["traffic lights"] == str(len(lane_map.traffic_lights))
    assert facts["crosswalks"] == str(len(lane_map.crosswalks))
    assert facts["sidewalks"] == str(len(lane_map.sidewalks))
    xmin, ymin, xmax, ymax = lane_map.bounds()
    assert facts["size"].startswith(f"{xmax - xmin:.1f} m x {ymax - ymin:.1f} m")


def test_town_facts_and_georeference(capsys: pytest.CaptureFixture[str]) -> None:
    facts = summary(run_map(capsys))  # the default map
    assert facts["map"] == "town"
    assert facts["size"].startswith("814.0 m x 814.0 m")
    assert facts["lanes"].startswith("608 (224 road lanes, 384 junction connectors")
    assert facts["georeference"].startswith("UTM zone 52N, local origin at easting 313000.000")
    lat, lon = (
        float(v) for v in re.findall(r"lat ([\d.]+), lon ([\d.]+)", facts["georeference"])[0]
    )
    assert lat == pytest.approx(37.58, abs=0.01) and lon == pytest.approx(126.88, abs=0.01)


NO_GEOREFERENCE_XODR = """<OpenDRIVE><header revMajor="1" revMinor="6"/>
  <road id="1" length="50" junction="-1">
    <planView><geometry s="0" x="0" y="0" hdg="0" length="50"><line/></geometry></planView>
    <lanes><laneSection s="0"><right><lane id="-1" type="driving">
      <width sOffset="0" a="3.5" b="0" c="0" d="0"/></lane></right></laneSection></lanes>
  </road></OpenDRIVE>"""


def test_a_map_naming_no_georeference_is_said_to_be_placed_by_assumption(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    path = tmp_path / "nowhere.xodr"
    path.write_text(NO_GEOREFERENCE_XODR)
    out = run_map(capsys, str(path))
    facts = summary(out)
    assert facts["georeference"].startswith(
        "assumed, the map names none: UTM zone 52N, local origin at easting 313000.000"
    )
    assert facts["georeference"].endswith("GPS latitudes and longitudes are invented")
    assert "note: header has no geoReference" in out
    # A map that names its own place is not said to be assumed.
    placed = summary(run_map(capsys, str(DATA_MAPS / "junction.xodr")))["georeference"]
    assert not placed.startswith("assumed")


def test_lanes_are_listed_with_their_start_poses(capsys: pytest.CaptureFixture[str]) -> None:
    lane_map = load_map("town")
    rows = table(run_map(capsys, "town", "--lanes"), "lane")
    assert set(rows) == set(lane_map.lanes)
    for lane_id, row in rows.items():
        lane = lane_map.lanes[lane_id]
        x, y, _, heading = lane_map.pose_at(lane_id, 0.0)
        assert float(row["x"]) == pytest.approx(x, abs=0.005)
        assert float(row["y"]) == pytest.approx(y, abs=0.005)
        assert float(row["heading_deg"]) == pytest.approx(math.degrees(heading), abs=0.05)
        assert float(row["length_m"]) == pytest.approx(lane.length, abs=0.005)
        assert row["light"] == (",".join(lane.traffic_light_ids) or "-")
        assert row["successors"] == ",".join(lane.successors)


def test_lights_and_crosswalks_are_listed_where_they_are(
    capsys: pytest.CaptureFixture[str],
) -> None:
    lane_map = load_map("town")
    out = run_map(capsys, "town", "--lights", "--crosswalks")
    lights, crosswalks = table(out, "light"), table(out, "crosswalk")
    assert set(lights) == set(lane_map.traffic_lights)
    for light_id, row in lights.items():
        light = lane_map.traffic_lights[light_id]
        assert (float(row["x"]), float(row["y"])) == pytest.approx(light.position[:2], abs=0.005)
        assert int(row["type"]) == light.light_type
        assert row["lanes"] == ",".join(light.lane_ids)
    assert set(crosswalks) == set(lane_map.crosswalks)
    for crosswalk_id, row in crosswalks.items():
        crosswalk = lane_map.crosswalks[crosswalk_id]
        assert (float(row["start_x"]), float(row["start_y"])) == pytest.approx(
            crosswalk.start, abs=0.005
        )
        assert (float(row["end_x"]), float(row["end_y"])) == pytest.approx(crosswalk.end, abs=0.005)


def test_a_map_without_lights_says_so(capsys: pytest.CaptureFixture[str]) -> None:
    out = run_map(capsys, "straight", "--lights", "--crosswalks")
    assert "no traffic lights" in out and "no crosswalks" in out


def test_png_is_written_and_decodes(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    path = tmp_path / "junction.png"
    out = run_map(capsys, str(DATA_MAPS / "junction.xodr"), "--png", str(path), "--size", "900")
    image = Image.open(io.BytesIO(path.read_bytes()))
    image.load()
    assert image.format == "PNG"
    assert max(image.size) > 900
    assert f"wrote {path} ({image.size[0]} x {image.size[1]} px): 11 of 11 road lane ids" in out
    assert "4 of 4 light ids labelled" in out


def test_docs_show_every_map_egosim_knows_by_name(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    docs = (DOCS_MAPS.parent / "maps.md").read_text()
    for name in map_names():
        assert f"](maps/{name}.png)" in docs
        committed = Image.open(DOCS_MAPS / f"{name}.png")
        fresh = tmp_path / f"{name}.png"
        run_map(capsys, name, "--png", str(fresh))
        # Same map, same default size: the committed picture is this map's, at this scale.
        assert committed.size == Image.open(fresh).size


def test_unknown_map_is_a_one_line_error() -> None:
    result = subprocess.run(
        [sys.executable, "-m", "egosim", "map", "no_such_map"],
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert result.returncode == 2
    known = ", ".join(map_names())
    assert result.stderr.strip().splitlines() == [
        f"egosim map: no_such_map: no such file or folder, nor a built-in map ({known})"
    ]
