"""Maps by name or path: the built-in maps, MGeo folders and OpenDRIVE (.xodr) files.

`load_map(name_or_path)` is what `egosim run --map NAME|PATH` calls. A built-in name gives
that map, the name of a map shipped with egosim (`mgeo_sample`) its folder; a folder is read
as MGeo, a `.xodr` file as OpenDRIVE. What a loader reads but
leaves out is logged (and returned by `read_map`); anything it cannot read raises a
MapLoadError whose one-line message names the file and the record.

A map read again (the same name, or the same files unchanged since) is the map read
before: maps are immutable, and a process that runs simulation after simulation (a batch
worker) builds each map, and what is derived from it, once.
"""

from __future__ import annotations

import json
import logging
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from egosim.world.map import BUILTIN_MAP_NAMES, LaneMap, MapRecordError, build_builtin_map
from egosim.world.map.mgeo import MGEO_FILES, build_mgeo_map
from egosim.world.map.opendrive import build_opendrive_map

OPENDRIVE_SUFFIX = ".xodr"
SHIPPED_MAPS_DIR = Path(__file__).parent / "data" / "maps"
"""Map folders shipped with egosim, loadable by their folder's name."""
MAPS_KEPT = 4
"""Maps read lately and kept for the next read of the same source."""

log = logging.getLogger(__name__)


class MapLoadError(Exception):
    """A map that cannot be loaded; the message is one line naming the file and record."""


@dataclass(frozen=True)
class LoadedMap:
    lane_map: LaneMap
    notes: tuple[str, ...]
    """What the loader read but left out, one line each."""


def shipped_map_names() -> tuple[str, ...]:
    return tuple(sorted(p.name for p in SHIPPED_MAPS_DIR.iterdir() if p.is_dir()))


def map_names() -> tuple[str, ...]:
    """Every map `load_map` knows by name: the built-in maps, then the shipped ones."""
    return (*BUILTIN_MAP_NAMES, *shipped_map_names())


def scenario_map_location(reference: str, scenario_folder: Path) -> str:
    """What to load for a scenario's `map` field: a known map name as it is, a path
    taken relative to the folder of the scenario file."""
    if reference in map_names():
        return reference
    path = Path(reference).expanduser()
    return str(path if path.is_absolute() else scenario_folder / path)


def load_map(name_or_path: str) -> LaneMap:
    """The map named (a built-in name) or stored at a path (an MGeo folder, a .xodr file)."""
    loaded = read_map(name_or_path)
    for note in loaded.notes:
        log.warning("map %s: %s", loaded.lane_map.name, note)
    return loaded.lane_map


def read_map(name_or_path: str) -> LoadedMap:
    """`load_map` that also returns the notes instead of logging them."""
    stamp = _source_stamp(name_or_path)
    if stamp is None:
        return _read_source(name_or_path)
    return _read_kept(name_or_path, stamp)


FileStamp = tuple[str, int, int]
"""A file's resolved path, modification time (ns) and size."""


def _source_stamp(name_or_path: str) -> tuple[FileStamp, ...] | None:
    """What tells one version of a map's files from another (nothing for a built-in map;
    None when the files cannot be looked at)."""
    if name_or_path in BUILTIN_MAP_NAMES:
        return ()
    path = SHIPPED_MAPS_DIR / name_or_path if name_or_path in shipped_map_names() else None
    path = path or Path(name_or_path)
    try:
        files = sorted(path.iterdir()) if path.is_dir() else [path]
        return tuple((str(f.resolve()), *_stat(f)) for f in files if f.is_file())
    except OSError:
        return None


def _stat(path: Path) -> tuple[int, int]:
    stat = path.stat()
    return stat.st_mtime_ns, stat.st_size


@lru_cache(maxsize=MAPS_KEPT)
def _read_kept(name_or_path: str, stamp: tuple[FileStamp, ...]) -> LoadedMap:
    """The map at `name_or_path` as its files are at `stamp` (errors are not kept)."""
    return _read_source(name_or_path)


def _read_source(name_or_path: str) -> LoadedMap:
    if name_or_path in BUILTIN_MAP_NAMES:
        return LoadedMap(build_builtin_map(name_or_path), ())
    if name_or_path in shipped_map_names():
        return _read_mgeo(SHIPPED_MAPS_DIR / name_or_path)
    path = Path(name_or_path)
    if path.is_dir():
        return _read_mgeo(path)
    if path.suffix.lower() == OPENDRIVE_SUFFIX and path.is_file():
        return _read_opendrive(path)
    if path.exists():
        raise MapLoadError(f"{path}: not an MGeo folder or an OpenDRIVE {OPENDRIVE_SUFFIX} file")
    known = ", ".join(map_names())
    raise MapLoadError(f"{name_or_path}: no such file or folder, nor a built-in map ({known})")


def _read_mgeo(folder: Path) -> LoadedMap:
    files: dict[str, object] = {}
    notes: list[str] = []
    for path in sorted(folder.iterdir()):
        if path.name in MGEO_FILES:
            files[path.name] = _read_json(path)
        elif path.suffix.lower() == ".json":
            notes.append(f"{path.name} not read")
    try:
        lane_map = build_mgeo_map(folder.resolve().name, files, notes)
    except MapRecordError as error:
        raise MapLoadError(f"{folder / error.source}: {error.record}: {error.reason}") from None
    return LoadedMap(lane_map, tuple(notes))


def _read_json(path: Path) -> object:
    try:
        return json.loads(path.read_bytes().decode("utf-8-sig"))
    except OSError as error:
        raise MapLoadError(f"{path}: {error.strerror}") from None
    except UnicodeDecodeError as error:
        raise MapLoadError(f"{path}: not UTF-8 text (byte {error.start})") from None
    except json.JSONDecodeError as error:
        raise MapLoadError(
            f"{path}: line {error.lineno} column {error.colno}: {error.msg}"
        ) from None


def _read_opendrive(path: Path) -> LoadedMap:
    notes: list[str] = []
    try:
        text = path.read_text(encoding="utf-8-sig")
    except OSError as error:
        raise MapLoadError(f"{path}: {error.strerror}") from None
    except UnicodeDecodeError as error:
        raise MapLoadError(f"{path}: not UTF-8 text (byte {error.start})") from None
    try:
        lane_map = build_opendrive_map(path.stem, text, notes)
    except MapRecordError as error:
        raise MapLoadError(f"{path}: {error.record}: {error.reason}") from None
    return LoadedMap(lane_map, tuple(notes))
