"""Scenario errors name the file, the line and the field; they are never tracebacks."""

import itertools
import textwrap

import jsonschema
import pytest

from egosim.world import World
from egosim.world.map import build_builtin_map
from egosim.world.scenario import Scenario, ScenarioError, parse_scenario, scenario_schema
from egosim.yamltext import YamlDocument

LABEL = "scenarios/bad.yaml"


def _error(text: str) -> ScenarioError:
    with pytest.raises(ScenarioError) as caught:
        parse_scenario(textwrap.dedent(text), LABEL)
    return caught.value


def test_unknown_field_is_located() -> None:
    error = _error(
        """\
        map: straight
        npcs:
          - start: {lane: R1_E_1, s: 10}
            colour: red
        """
    )
    assert (error.label, error.line, error.field) == (LABEL, 4, "npcs[0].colour")
    assert str(error) == f"{LABEL}:4: npcs[0].colour: unknown field 'colour'"


def test_wrong_type_is_located() -> None:
    error = _error(
        """\
        map: straight
        seed: lots
        """
    )
    assert (error.line, error.field) == (2, "seed")
    assert "integer" in error.message


def test_out_of_range_value_is_located() -> None:
    error = _error(
        """\
        map: straight
        pedestrians:
          - sidewalk: SW1
          - sidewalk: SW2
            speed_mps: -1.0
        """
    )
    assert (error.line, error.field) == (5, "pedestrians[1].speed_mps")


def test_missing_map_is_reported_at_the_top() -> None:
    error = _error("seed: 3\n")
    assert error.line == 1
    assert "'map' is a required property" in str(error)


def test_yaml_syntax_error_names_its_line() -> None:
    error = _error(
        """\
        map: straight
        npcs:
          - start: {lane: R1_E_1
        obstacles: []
        """
    )
    assert error.label == LABEL
    assert error.line in (3, 4)
    assert "not valid YAML" in error.message


def test_duplicate_key_is_an_error() -> None:
    error = _error("map: straight\nseed: 1\nseed: 2\n")
    assert (error.line, error.field) == (3, "seed")


def test_unknown_lane_is_located_when_placed_on_the_map() -> None:
    scenario = parse_scenario(
        textwrap.dedent(
            """\
            map: straight
            npcs:
              - start: {lane: R1_E_1, s: 10}
              - start:
                  lane: R7_Z_9
            """
        ),
        LABEL,
    )
    with pytest.raises(ScenarioError) as caught:
        World(build_builtin_map("straight"), scenario)
    assert (caught.value.line, caught.value.field) == (5, "npcs[1].start.lane")


def test_unknown_model_and_map_mismatch_are_located() -> None:
    lane_map = build_builtin_map("straight")
    scenario = parse_scenario(
        "map: straight\nego:\n  model: Trabant\n  start: {x: 0, y: 0}\n", LABEL
    )
    with pytest.raises(ScenarioError) as caught:
        World(lane_map, scenario)
    assert (caught.value.line, caught.value.field) == (3, "ego.model")
    with pytest.raises(ScenarioError) as caught:
        World(lane_map, parse_scenario("map: town\n", LABEL))
    assert (caught.value.line, caught.value.field) == (1, "map")


def test_schema_is_a_valid_json_schema() -> None:
    jsonschema.Draft202012Validator.check_schema(scenario_schema())


def _alias_bomb(levels: int) -> str:
    """A few hundred bytes whose aliases expand to 10**levels values."""
    names = [f"l{k}" for k in range(levels + 1)]
    text = f"network:\n  {names[0]}: &{names[0]} [x, x, x, x, x, x, x, x, x, x]\n"
    for previous, name in itertools.pairwise(names):
        text += f"  {name}: &{name} [{', '.join([f'*{previous}'] * 10)}]\n"
    return "map: straight\n" + text


@pytest.mark.parametrize(
    ("text", "line", "message"),
    [
        (_alias_bomb(8), None, "more than 200000 values"),
        ("map: straight\nnetwork: &loop\n  again: *loop\n", 2, "nested too deep (or in itself)"),
        ("map: straight\nseed: " + "9" * 5000 + "\n", 2, "bad value: Exceeds the limit"),
        ("map: straight\n? [a]\n: 1\n", 2, "a key must be a plain value"),
    ],
)
def test_a_file_yaml_cannot_safely_build_is_an_error(
    text: str, line: int | None, message: str
) -> None:
    error = _error(text)
    assert error.label == LABEL
    assert error.line is not None and (line is None or error.line == line)
    assert message in str(error)


def test_a_scenario_built_in_code_raises_scenario_errors() -> None:
    document = YamlDocument("my_scenario.py", {"map": "town"}, {("map",): 3})
    error = Scenario(map_name="town", source=document).error(("map",), "no such map")
    assert isinstance(error, ScenarioError)
    assert (error.label, error.line, error.field) == ("my_scenario.py", 3, "map")
    assert str(error) == "my_scenario.py:3: map: no such map"
