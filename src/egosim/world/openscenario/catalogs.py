"""Catalogues: the entries of catalogue files, and CatalogReference resolved with its
ParameterAssignments.

The files are handed over as texts (the caller reads the directories a scenario's
<CatalogLocations> name). A reference's catalogName is the <Catalog name> of a file, its
entryName the entry's name; both may be parameters. The entry is read in a scope of its
own declared parameters, with the assignments in place of their defaults and the
scenario's parameters behind them.
"""

from __future__ import annotations

from collections.abc import Iterable

from egosim.world.openscenario.parameters import Scope, assignments, declare
from egosim.world.openscenario.reading import Element
from egosim.world.openscenario.xmltree import Node, parse_xml

CATALOG_TYPES = (
    "VehicleCatalog",
    "ControllerCatalog",
    "PedestrianCatalog",
    "MiscObjectCatalog",
    "EnvironmentCatalog",
    "ManeuverCatalog",
    "TrajectoryCatalog",
    "RouteCatalog",
)


class Catalogs:
    """Every entry of the catalogue files, by catalogue name and entry name."""

    def __init__(self, files: Iterable[tuple[str, str | bytes]], notes: list[str]) -> None:
        self._entries: dict[str, dict[str, Node]] = {}
        for label, text in files:
            root = parse_xml(text, label)
            catalog = root.child("Catalog")
            if catalog is None:
                continue  # a scenario or another file lying in a catalogue directory
            name = catalog.get("name") or ""
            entries = self._entries.setdefault(name, {})
            for entry in catalog.children():
                entry_name = entry.get("name")
                if entry_name is None:
                    notes.append(entry.note("has no name; not usable from a CatalogReference"))
                elif entry_name in entries:
                    notes.append(entry.note(f"{entry_name!r} is defined again; the first is used"))
                else:
                    entries[entry_name] = entry

    def names(self) -> list[str]:
        return sorted(self._entries)

    def resolve(self, reference: Element, root: Scope) -> Element:
        """The entry a <CatalogReference> names, in its own parameter scope."""
        catalog = reference.text("catalogName")
        name = reference.text("entryName")
        entries = self._entries.get(catalog)
        if entries is None:
            known = ", ".join(self.names()) or "none were found"
            raise reference.node.error(f"no catalogue {catalog!r} (catalogues: {known})")
        entry = entries.get(name)
        if entry is None:
            raise reference.node.error(f"catalogue {catalog!r} has no entry {name!r}")
        given = assignments(reference.node.child("ParameterAssignments"), reference.scope)
        scope = root.child()
        declare(entry.child("ParameterDeclarations"), scope, given)
        return Element(entry, scope)


def catalog_directories(root: Node) -> list[tuple[str, str]]:
    """(catalogue type, directory path as written) of a scenario's <CatalogLocations>."""
    locations = root.child("CatalogLocations")
    if locations is None:
        return []
    found = []
    for location in locations.children():
        for directory in location.children("Directory"):
            path = directory.get("path")
            if path:
                found.append((location.tag, path))
    return found
