"""Suite files (YAML, validated against suite.schema.json) -> concrete cases."""

from __future__ import annotations

import copy
import csv
import json
import string
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from functools import cache
from importlib import resources
from pathlib import Path

import jsonschema

from egosim.batch.case import DEFAULT_TIME_LIMIT_S, CaseSpec, StackSpec
from egosim.batch.errors import SuiteError
from egosim.batch.sweep import Value, case_name, format_value, parameter_sets
from egosim.evaluation import METRIC_NAMES, CriterionError, InfractionKind, parse_criterion
from egosim.json_value import JsonObject, JsonValue
from egosim.maps import scenario_map_location
from egosim.scenario_files import is_morai_scenario, is_openscenario, read_openscenario_file
from egosim.world.map import BUILTIN_MAP_NAMES
from egosim.world.openscenario.distributions import is_distribution, read_distribution
from egosim.world.openscenario.program import root_of
from egosim.world.scenario import ScenarioError, parse_scenario
from egosim.world.scenario.morai import morai_document, read_morai_scenario
from egosim.yamltext import (
    FieldPath,
    YamlDocument,
    YamlFileError,
    as_list,
    as_number,
    as_object,
    as_text,
    list_at,
    number_at,
    object_at,
    objects_at,
    optional_text_at,
    parse_yaml,
    text_at,
)

DEFAULT_CRITERIA = ("no_collision",)


@dataclass(frozen=True)
class ScenarioLayout:
    """Where a scenario format keeps what parameters set, and how a case's scenario is
    checked."""

    counted_lists: Mapping[str, str]
    """Parameters that keep the first N entries of a scenario list."""
    fields: Mapping[str, str]
    """Parameters that set a scenario field directly."""
    check: Callable[[JsonValue, str], object]
    """Raises ScenarioError for a scenario (data, label) that cannot be used."""


YAML_LAYOUT = ScenarioLayout(
    {"npc_count": "npcs", "pedestrian_count": "pedestrians"}, {"seed": "seed"}, parse_scenario
)
MORAI_LAYOUT = ScenarioLayout(
    {"npc_count": "vehicleList", "pedestrian_count": "pedestrianList"},
    {},
    lambda data, label: read_morai_scenario(json.dumps(data), label),
)


@cache
def suite_schema() -> JsonObject:
    """The JSON Schema of suite files."""
    text = resources.files(__package__).joinpath("suite.schema.json").read_text("utf-8")
    return as_object(json.loads(text))


def load_suite(path: Path) -> list[CaseSpec]:
    """The concrete cases of the suite file at `path`, in file and sweep order."""
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise SuiteError(str(path), None, "", f"cannot read: {error}") from None
    return _cases(parse_yaml(text, str(path), SuiteError), path.resolve().parent)


def scenario_suite(path: Path, stack: str, time_limit_s: float, clock: str) -> list[CaseSpec]:
    """The cases of one OpenSCENARIO file, ParameterValueDistribution file or MORAI
    scenario file run with the stack command `stack` (`egosim batch FILE.xosc --stack
    COMMAND`)."""
    data: JsonObject = {
        "stack": {"command": stack},
        "clock": clock,
        "time_limit_s": time_limit_s,
        "cases": [{"name": path.stem, "scenario": path.name}],
    }
    return _cases(YamlDocument(str(path), data, error_type=SuiteError), path.resolve().parent)


def _cases(source: YamlDocument, suite_dir: Path) -> list[CaseSpec]:
    _validate(source)
    data = as_object(source.data)
    cases: list[CaseSpec] = []
    for k, entry in enumerate(objects_at(data, "cases")):
        cases.extend(_expand(source, ("cases", k), entry, suite_dir))
    names = [case.name for case in cases]
    for k, name in enumerate(names):
        if name in names[:k]:
            raise source.error(("cases",), f"two cases are named {name!r}")
    return cases


def _validate(source: YamlDocument) -> None:
    validator = jsonschema.Draft202012Validator(suite_schema())
    error = jsonschema.exceptions.best_match(validator.iter_errors(source.data))
    if error is not None:
        raise source.error(tuple(error.absolute_path), error.message)
    data = as_object(source.data)
    for path, criteria in _criteria_lists(data):
        for k, text in enumerate(criteria):
            try:
                parse_criterion(text, METRIC_NAMES)
            except CriterionError as problem:
                raise source.error((*path, k), str(problem)) from None
    kinds = {kind.value for kind in InfractionKind}
    for kind in object_at(object_at(data, "scoring") or {}, "penalties") or {}:
        if kind not in kinds:
            known = ", ".join(sorted(kinds))
            raise source.error(("scoring", "penalties", kind), f"no infraction {kind!r}; {known}")


def _criteria_lists(data: JsonObject) -> list[tuple[FieldPath, list[str]]]:
    found: list[tuple[FieldPath, list[str]]] = []
    if "criteria" in data:
        found.append((("criteria",), _texts(data["criteria"])))
    for k, case in enumerate(objects_at(data, "cases")):
        if "criteria" in case:
            found.append((("cases", k, "criteria"), _texts(case["criteria"])))
    return found


def _texts(value: JsonValue) -> list[str]:
    return [as_text(item) for item in as_list(value)]


def _value(value: JsonValue) -> Value:
    """A parameter's value (the schema's number, string or boolean)."""
    if not isinstance(value, bool | int | float | str):
        raise TypeError(f"expected a parameter value, got {value!r}")
    return value


def _values(data: JsonObject | None) -> dict[str, Value]:
    return {key: _value(value) for key, value in (data or {}).items()}


def _parameter_sets(entry: JsonObject) -> list[dict[str, Value]]:
    """The parameter sets of an entry's `sweep` and `combinations`."""
    sweep: dict[str, list[Value] | dict[str, float]] = {}
    for name, spec in (object_at(entry, "sweep") or {}).items():
        if isinstance(spec, dict):
            sweep[name] = {key: as_number(bound) for key, bound in spec.items()}
        else:
            sweep[name] = [_value(item) for item in as_list(spec)]
    combinations = [_values(as_object(c)) for c in list_at(entry, "combinations")]
    return parameter_sets(sweep, combinations)


def _expand(
    source: YamlDocument, path: FieldPath, entry: JsonObject, suite_dir: Path
) -> list[CaseSpec]:
    data = as_object(source.data)
    scenario_path = suite_dir / text_at(entry, "scenario")
    if is_openscenario(scenario_path):
        return _openscenario_cases(source, path, entry, scenario_path, suite_dir)
    morai = is_morai_scenario(scenario_path)
    layout = MORAI_LAYOUT if morai else YAML_LAYOUT
    try:
        scenario_text = scenario_path.read_text(encoding="utf-8")
        scenario_data: JsonValue = (
            morai_document(scenario_text, str(scenario_path))
            if morai
            else parse_yaml(scenario_text, str(scenario_path), ScenarioError).data
        )
    except (OSError, UnicodeDecodeError) as error:
        raise source.error((*path, "scenario"), f"cannot read: {error}") from None
    except YamlFileError as error:
        raise source.error((*path, "scenario"), str(error)) from None
    try:
        sets = _parameter_sets(entry)
    except ValueError as error:
        raise source.error((*path, "sweep"), str(error)) from None
    stack_spec = _stack(data)
    route = _route(source, path, object_at(entry, "route"), suite_dir)
    if morai:
        map_name: JsonValue = _morai_map(entry, scenario_data, scenario_path, suite_dir)
    else:
        map_name = entry.get(
            "map", scenario_data.get("map") if isinstance(scenario_data, dict) else None
        )
        if isinstance(map_name, str) and map_name not in BUILTIN_MAP_NAMES and "map" in entry:
            map_name = str(suite_dir / map_name)
    cases = []
    defaults = {**_parameters(data), **_parameters(entry)}
    for swept in sets:
        name = case_name(text_at(entry, "name"), swept)
        where = (*path, "sweep") if swept else path
        parameters = {**defaults, **swept}
        scenario = _apply(source, where, name, scenario_data, parameters, stack_spec, layout)
        case = _case(data, entry, name, scenario_path, parameters, suite_dir, str(map_name), route)
        cases.append(replace(case, scenario=scenario))
    return cases


def _parameters(data: JsonObject) -> dict[str, Value]:
    return _values(object_at(data, "parameters"))


def _morai_map(
    entry: JsonObject, data: JsonValue, scenario_path: Path, suite_dir: Path
) -> str | None:
    """The map a MORAI case runs: the entry's `map`, else the file's mapInfo.mapName (a
    map name, or a map folder beside the file)."""
    if "map" in entry:
        given = str(entry["map"])
        return given if given in BUILTIN_MAP_NAMES else str(suite_dir / given)
    info = data.get("mapInfo") if isinstance(data, dict) else None
    name = info.get("mapName") if isinstance(info, dict) else None
    if not isinstance(name, str) or not name:
        return None
    return scenario_map_location(name, scenario_path.parent)


def _stack(data: JsonObject) -> StackSpec:
    stack = as_object(data["stack"])
    return StackSpec(
        command=text_at(stack, "command"),
        env={k: str(v) for k, v in (object_at(stack, "env") or {}).items()},
        connect_timeout_s=number_at(stack, "connect_timeout_s", 30.0),
    )


def _case(
    data: JsonObject,
    entry: JsonObject,
    name: str,
    scenario_path: Path,
    parameters: dict[str, Value],
    suite_dir: Path,
    map_name: str,
    route: JsonObject | None,
) -> CaseSpec:
    """A case with the fields that do not depend on the scenario's format (its scenario
    still empty)."""
    clock = data.get("clock", "sim")
    if isinstance(clock, str):
        mode, rtf = clock, 0.0
    else:
        clock = as_object(clock)
        mode, rtf = text_at(clock, "mode"), number_at(clock, "rtf", 0.0)
    suite_limit = number_at(data, "time_limit_s", DEFAULT_TIME_LIMIT_S)
    time_limit = number_at(entry, "time_limit_s", suite_limit)
    criteria = entry.get("criteria", data.get("criteria"))
    return CaseSpec(
        name=name,
        scenario={},
        scenario_file=str(scenario_path),
        parameters=parameters,
        stack=_stack(data),
        suite_dir=str(suite_dir),
        map=map_name,
        route=route,
        clock=mode,
        rtf=rtf,
        time_limit_s=time_limit,
        wall_limit_s=number_at(data, "wall_limit_s", 120.0 + 10.0 * time_limit),
        criteria=DEFAULT_CRITERIA if criteria is None else tuple(_texts(criteria)),
        scoring=dict(object_at(data, "scoring") or {}),
        bags=text_at(data, "bags", "all"),
    )


def _openscenario_cases(
    source: YamlDocument,
    path: FieldPath,
    entry: JsonObject,
    file: Path,
    suite_dir: Path,
) -> list[CaseSpec]:
    """The cases of an OpenSCENARIO file (the suite's sweep sets its declared
    parameters), or of a ParameterValueDistribution file: one case per concrete
    parameter set, named by the values the distribution gives."""
    data = as_object(source.data)
    where = (*path, "scenario")
    try:
        text = file.read_bytes()
        distribution = (
            read_distribution(text, str(file))
            if is_distribution(root_of(text, str(file)))
            else None
        )
    except OSError as error:
        raise source.error(where, f"cannot read: {error}") from None
    except ScenarioError as error:
        raise source.error(where, str(error)) from None
    if distribution is not None:
        scenario_file = (file.parent / distribution.scenario_file).resolve()
        variants: list[dict[str, Value]] = [dict(case) for case in distribution.cases]
        named = _varying(variants)
        if "sweep" in entry or "combinations" in entry:
            raise source.error((*path, "sweep"), "a ParameterValueDistribution is its own sweep")
    else:
        scenario_file = file
        try:
            variants = _parameter_sets(entry)
        except ValueError as error:
            raise source.error((*path, "sweep"), str(error)) from None
        named = None
    stack = _stack(data)
    route = _route(source, path, object_at(entry, "route"), suite_dir)
    defaults = {**_parameters(data), **_parameters(entry)}
    cases = []
    declared: set[str] | None = None
    for variant in variants:
        shown = variant if named is None else {k: v for k, v in variant.items() if k in named}
        name = case_name(text_at(entry, "name"), shown)
        parameters = {**defaults, **variant}
        declared = declared if declared is not None else _declared(source, where, scenario_file)
        unused = [k for k in parameters if k not in declared and k not in _stack_fields(stack)]
        if unused:
            message = f"case {name}: parameter {unused[0]!r} is used by neither scenario nor stack"
            raise source.error(path, message)
        values = {k: format_value(v) for k, v in parameters.items() if k in declared}
        try:
            scenario = read_openscenario_file(scenario_file, parameters=values, log_notes=False)
        except (OSError, ScenarioError) as error:
            raise source.error(where, f"case {name}: {error}") from None
        map_name = optional_text_at(entry, "map")
        location = (
            str(suite_dir / map_name)
            if map_name is not None and map_name not in BUILTIN_MAP_NAMES
            else map_name or scenario_map_location(scenario.map_reference, scenario_file.parent)
        )
        case = _case(data, entry, name, file, parameters, suite_dir, location, route)
        cases.append(replace(case, openscenario=str(scenario_file), scenario_parameters=values))
    return cases


def _varying(variants: list[dict[str, Value]]) -> set[str]:
    """The parameters whose value differs between the cases (what names each one)."""
    keys = {key for variant in variants for key in variant}
    return {key for key in keys if len({str(v.get(key)) for v in variants}) > 1}


def _declared(source: YamlDocument, where: FieldPath, file: Path) -> set[str]:
    try:
        return set(read_openscenario_file(file, log_notes=False).parameters)
    except (OSError, ScenarioError) as error:
        raise source.error(where, str(error)) from None


def _route(
    source: YamlDocument, path: FieldPath, route: JsonObject | None, suite_dir: Path
) -> JsonObject | None:
    if route is None or "csv" not in route:
        return route
    csv_path = suite_dir / text_at(route, "csv")
    try:
        with csv_path.open(encoding="utf-8", newline="") as file:
            points: list[JsonValue] = [
                [float(row["x"]), float(row["y"])] for row in csv.DictReader(file)
            ]
    except (OSError, UnicodeDecodeError, KeyError, ValueError, TypeError) as error:
        message = f"cannot read x, y columns from {csv_path}: {error!r}"
        raise source.error((*path, "route", "csv"), message) from None
    resolved = {k: v for k, v in route.items() if k != "csv"}
    resolved["waypoints"] = points
    return resolved


def _apply(
    source: YamlDocument,
    path: FieldPath,
    name: str,
    scenario: JsonValue,
    parameters: Mapping[str, Value],
    stack: StackSpec,
    layout: ScenarioLayout,
) -> JsonObject:
    """The scenario with `$parameter` values replaced, its fields set and lists cut to
    their counts (as `layout` says); every parameter must be used somewhere (scenario or
    stack)."""
    used: set[str] = set()

    def substitute(value: JsonValue) -> JsonValue:
        if isinstance(value, dict):
            return {k: substitute(v) for k, v in value.items()}
        if isinstance(value, list):
            return [substitute(v) for v in value]
        if isinstance(value, str) and value.startswith("$"):
            key = value[1:]
            if key not in parameters:
                raise source.error(path, f"case {name}: the scenario uses {value}, not set")
            used.add(key)
            return parameters[key]
        return value

    substituted = substitute(copy.deepcopy(scenario))
    # Not a mapping: the check below refuses it, once every parameter is accounted for.
    result = substituted if isinstance(substituted, dict) else {}
    for key, value in parameters.items():
        if key in layout.fields:
            result[layout.fields[key]] = value
            used.add(key)
        elif key in layout.counted_lists:
            listed = result.get(layout.counted_lists[key], [])
            # Not a list: the check below refuses it.
            entries = listed if isinstance(listed, list) else []
            if not isinstance(value, int) or not 0 <= value <= len(entries):
                message = f"case {name}: {key} must be 0..{len(entries)} (the scenario's list)"
                raise source.error(path, message)
            if isinstance(listed, list):
                result[layout.counted_lists[key]] = entries[:value]
            used.add(key)
    used |= _stack_fields(stack) & set(parameters)
    unused = [key for key in parameters if key not in used]
    if unused:
        message = f"case {name}: parameter {unused[0]!r} is used by neither scenario nor stack"
        raise source.error(path, message)
    try:
        layout.check(substituted, f"{name} ({source.label})")
    except ScenarioError as error:
        raise source.error(path, str(error)) from None
    return result


def _stack_fields(stack: StackSpec) -> set[str]:
    """The {names} the stack's command and environment use."""
    names: set[str] = set()
    for text in (stack.command, *stack.env.values()):
        for _, field_name, _, _ in string.Formatter().parse(text):
            if field_name:
                names.add(field_name)
    return names
