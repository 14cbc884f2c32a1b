"""Malformed and odd OpenSCENARIO files: the gallery's files with attribute values
replaced by odd ones, elements taken out or doubled, and texts cut short. Each is
either read, loaded and run for a while without an exception, or refused with one
ScenarioError naming the file and line; never another exception."""

from __future__ import annotations

import re
from functools import cache
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lxml import etree
from tests.world.openscenario.stories import highway

from egosim.scenario_files import openscenario_scenario
from egosim.world import World
from egosim.world.openscenario import read_openscenario
from egosim.world.scenario import ScenarioError, ScenarioLoadOptions

GALLERY = Path(__file__).parents[3] / "examples" / "openscenario"
FILES = ("cut_in.xosc", "braking_target.xosc", "pedestrian_crossing.xosc")
ODD_VALUES = (
    "",
    " ",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "-1",
    "0",
    "-0",
    "1e308",
    "-1e308",
    "1e-320",
    "99999999999999999999",
    "abc",
    "true",
    "${1/0}",
    "${1 % 0}",
    "${",
    "${sqrt(-1)}",
    "${pow(10, 400)}",
    "${acos(2)}",
    "$undeclared",
    "$",
    "${$x + }",
    "Ego",
    "Target",
    "-1.5",
    "3",
)
ATTRIBUTE = re.compile(r'(\w+)="([^"]*)"')
ERROR_LINE = re.compile(r"^\S+\.xosc(:\d+)?: \S")
CHECKED = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@cache
def texts() -> dict[str, str]:
    return {name: (GALLERY / name).read_text() for name in FILES}


@cache
def catalogs() -> tuple[tuple[str, str], ...]:
    return tuple(
        (str(path), path.read_text()) for path in sorted((GALLERY / "catalogs").glob("*.xosc"))
    )


def read_load_and_run(text: str | bytes, label: str = "fuzzed.xosc") -> None:
    try:
        program = read_openscenario(text, label, catalogs())
        world = World(highway())
        world.load_scenario(
            openscenario_scenario(program), ScenarioLoadOptions(scenario_drives_ego=True)
        )
    except ScenarioError as error:
        # One line per mistake, each naming its file (and line where it has one).
        lines = str(error).strip().splitlines()
        assert lines, "an empty error"
        for line in lines:
            assert ERROR_LINE.match(line), line
        return
    run = world.storyboard
    assert run is not None
    for _ in range(20):
        run.step(0.1, True)
        world.step(0.1)


@CHECKED
@given(
    st.sampled_from(FILES),
    st.lists(
        st.tuples(st.integers(0, 10_000), st.sampled_from(ODD_VALUES)), min_size=1, max_size=3
    ),
)
def test_odd_attribute_values_are_read_or_refused_with_the_line(
    name: str, changes: list[tuple[int, str]]
) -> None:
    text = texts()[name]
    for where, value in changes:
        matches = list(ATTRIBUTE.finditer(text))
        match = matches[where % len(matches)]
        text = text[: match.start(2)] + value + text[match.end(2) :]
    read_load_and_run(text)


@CHECKED
@given(st.sampled_from(FILES), st.integers(0, 10_000), st.booleans())
def test_elements_taken_out_or_doubled_are_read_or_refused(
    name: str, where: int, double: bool
) -> None:
    root = etree.fromstring(texts()[name].encode())
    elements = [e for e in root.iter() if isinstance(e.tag, str) and e is not root]
    element = elements[where % len(elements)]
    parent = element.getparent()
    assert parent is not None
    if double:
        parent.insert(parent.index(element), etree.fromstring(etree.tostring(element)))
    else:
        parent.remove(element)
    read_load_and_run(etree.tostring(root))


@CHECKED
@given(st.sampled_from(FILES), st.integers(0, 10_000))
def test_texts_cut_short_are_refused_with_the_line(name: str, where: int) -> None:
    text = texts()[name]
    read_load_and_run(text[: where % len(text)])


@CHECKED
@given(st.binary(max_size=200))
def test_bytes_that_are_no_scenario_are_refused(data: bytes) -> None:
    read_load_and_run(data)
