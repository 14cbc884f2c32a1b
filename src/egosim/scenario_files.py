"""Scenario files by path: egosim's YAML, ASAM OpenSCENARIO XML (.xosc), with the
catalogue files an OpenSCENARIO scenario's <CatalogLocations> name, and MORAI SIM's own
scenario files (.json, as its scenario editor saves them).

`read_scenario_file(path)` is what `egosim run --scenario`, ScenarioLoad, the live view
and batch cases read with. An OpenSCENARIO file's catalogue directories are taken
relative to the file; with `roots` (a name that came from the network) they must lie
inside those data roots. What a file holds that egosim reads but does not carry out is
logged, one line each: an OpenSCENARIO element with its file:line, a MORAI field by name
with the entries that have it.
"""

from __future__ import annotations

import logging
from collections.abc import Mapping, Sequence
from pathlib import Path

from egosim.datapaths import PathOutsideRootsError, read_regular_file, resolve_in_roots
from egosim.world.openscenario import (
    OpenScenario,
    catalog_directories,
    map_reference,
    read_openscenario,
    root_of,
)
from egosim.world.scenario import Scenario, ScenarioError, parse_scenario
from egosim.world.scenario.model import map_name_of
from egosim.world.scenario.morai import read_morai_scenario
from egosim.yamltext import YamlDocument

OPENSCENARIO_SUFFIX = ".xosc"
MORAI_SUFFIX = ".json"
YAML_SUFFIXES = (".yaml", ".yml")
SCENARIO_SUFFIXES = ("", *YAML_SUFFIXES, OPENSCENARIO_SUFFIX, MORAI_SUFFIX)
"""What a scenario name may leave out (ScenarioLoad names a file with or without it)."""
MORAI_KEYS = (b'"egoVehicle"', b'"mapInfo"', b'"vehicleList"', b'"pedestrianList"')
"""Top-level keys of a MORAI scenario; one of them opens every file MORAI saves."""
SNIFFED_BYTES = 4096

log = logging.getLogger("egosim.openscenario")
morai_log = logging.getLogger("egosim.morai")


def is_openscenario(path: Path) -> bool:
    return path.suffix.lower() == OPENSCENARIO_SUFFIX


def is_morai_scenario(path: Path) -> bool:
    return path.suffix.lower() == MORAI_SUFFIX


def looks_like_scenario(path: Path) -> bool:
    """A file a scenario list should offer: YAML and OpenSCENARIO by their suffix, a .json
    file when it opens as MORAI's scenarios do (a data root may hold other JSON: MGeo
    maps, batch results)."""
    suffix = path.suffix.lower()
    if suffix in (*YAML_SUFFIXES, OPENSCENARIO_SUFFIX):
        return path.is_file()
    if suffix != MORAI_SUFFIX or not path.is_file():
        return False
    try:
        with path.open("rb") as file:
            head = file.read(SNIFFED_BYTES)
    except OSError:
        return False
    return any(key in head for key in MORAI_KEYS)


def read_scenario_file(
    path: Path,
    parameters: Mapping[str, str] | None = None,
    roots: Sequence[Path] | None = None,
) -> Scenario:
    """The scenario in the file at `path` (OSError, UnicodeDecodeError, ScenarioError);
    `parameters` set an OpenSCENARIO file's declared parameters."""
    data = read_regular_file(path)
    if is_openscenario(path):
        return openscenario_scenario(read_openscenario_file(path, data, parameters, roots))
    if parameters:
        raise ScenarioError(str(path), None, "", "parameters apply to OpenSCENARIO files only")
    if is_morai_scenario(path):
        return read_morai_file(path, data)
    return parse_scenario(data.decode("utf-8"), str(path))


def read_morai_file(path: Path, data: bytes | None = None, log_notes: bool = True) -> Scenario:
    """A MORAI scenario file; what it asks that egosim does not do is logged, one line
    per field name (unless log_notes is false: a suite checks its cases' files)."""
    data = read_regular_file(path) if data is None else data
    read = read_morai_scenario(data, str(path))
    for note in read.notes if log_notes else ():
        morai_log.warning("%s", note)
    return read.scenario


def read_openscenario_file(
    path: Path,
    data: bytes | None = None,
    parameters: Mapping[str, str] | None = None,
    roots: Sequence[Path] | None = None,
    log_notes: bool = True,
) -> OpenScenario:
    """An OpenSCENARIO file read with its catalogues; its notes are logged (unless
    log_notes is false: a suite checks its cases' files)."""
    data = read_regular_file(path) if data is None else data
    label = str(path)
    root = root_of(data, label)
    catalogs = []
    for kind, directory in catalog_directories(root):
        catalogs += _catalog_files(path.parent, kind, directory, label, roots)
    scenario = read_openscenario(data, label, catalogs, parameters)
    for note in scenario.notes if log_notes else ():
        log.warning("%s", note)
    return scenario


def _catalog_files(
    folder: Path, kind: str, directory: str, label: str, roots: Sequence[Path] | None
) -> list[tuple[str, bytes]]:
    where = Path(directory)
    where = where if where.is_absolute() else folder / where
    try:
        if roots is not None:
            where = resolve_in_roots(str(where), roots)
        files = sorted(p for p in where.iterdir() if p.suffix.lower() == OPENSCENARIO_SUFFIX)
    except (OSError, PathOutsideRootsError) as error:
        log.warning("%s: <%s> directory %s not read: %s", label, kind, directory, error)
        return []
    found = []
    for file in files:
        try:
            found.append((str(file), read_regular_file(file)))
        except OSError as error:
            log.warning("%s: catalogue %s not read: %s", label, file, error)
    return found


def openscenario_scenario(scenario: OpenScenario) -> Scenario:
    """The Scenario egosim loads for an OpenSCENARIO file: its map (the LogicFile,
    relative to the file) and its storyboard."""
    return Scenario(
        map_name=map_name_of(scenario.map_reference),
        map_reference=scenario.map_reference,
        storyboard=scenario,
        source=YamlDocument(scenario.label, None, error_type=ScenarioError),
    )


__all__ = [
    "MORAI_SUFFIX",
    "OPENSCENARIO_SUFFIX",
    "SCENARIO_SUFFIXES",
    "is_morai_scenario",
    "is_openscenario",
    "looks_like_scenario",
    "map_reference",
    "openscenario_scenario",
    "read_morai_file",
    "read_openscenario_file",
    "read_scenario_file",
]
