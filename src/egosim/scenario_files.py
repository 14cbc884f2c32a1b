"""Scenario files by path: egosim's YAML and ASAM OpenSCENARIO XML (.xosc), with the
catalogue files an OpenSCENARIO scenario's <CatalogLocations> name.

`read_scenario_file(path)` is what `egosim run --scenario`, ScenarioLoad and batch cases
read with. An OpenSCENARIO file's catalogue directories are taken relative to the file;
with `roots` (a name that came from the network) they must lie inside those data roots.
What a file holds that egosim reads but does not carry out is logged, one line each,
naming the element and its file:line.
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
from egosim.yamltext import YamlDocument

OPENSCENARIO_SUFFIX = ".xosc"
SCENARIO_SUFFIXES = ("", ".yaml", ".yml", OPENSCENARIO_SUFFIX)
"""What a scenario name may leave out (ScenarioLoad names a file with or without it)."""

log = logging.getLogger("egosim.openscenario")


def is_openscenario(path: Path) -> bool:
    return path.suffix.lower() == OPENSCENARIO_SUFFIX


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
    return parse_scenario(data.decode("utf-8"), str(path))


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
    "OPENSCENARIO_SUFFIX",
    "SCENARIO_SUFFIXES",
    "is_openscenario",
    "map_reference",
    "openscenario_scenario",
    "read_openscenario_file",
    "read_scenario_file",
]
