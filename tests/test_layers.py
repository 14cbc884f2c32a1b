"""The architecture's import rules (docs/ARCHITECTURE.md): imports point down the layers,
the pure core never reaches the ROS side, the bridge's protocol storey stands on nothing
else of the bridge, and no modules import each other in a circle.

Every import counts, those under `if TYPE_CHECKING:` and inside functions too.
"""

from __future__ import annotations

import graphlib

import grimp
import pytest

# Top to bottom; a module may import its own layer and the layers below it.
LAYERS = (
    "cli",
    "batch",
    "view",
    "app",
    "report",
    "render",
    "plots",
    "bridge",
    "replay",
    "evaluation",
    "scenario_files",
    "maps",
    "sensors",
    "world",
    "ros1",
    "msgs",
    "yamltext",
    "datapaths",
    "logthrottle",
    "json_value",
)
# Below in the order, yet out of reach: the pure core knows no ROS, ROS knows no driving.
PURE = ("evaluation", "scenario_files", "maps", "sensors", "world")
ROS_SIDE = ("ros1", "msgs")
# The bridge's bottom storey: the table, its settings, codes, units and releases.
BRIDGE_PROTOCOL = "egosim.bridge.protocol"


@pytest.fixture(scope="module")
def imports() -> dict[str, set[str]]:
    graph = grimp.build_graph("egosim", include_external_packages=False)
    return {module: graph.find_modules_directly_imported_by(module) for module in graph.modules}


def layer_of(module: str) -> str | None:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[1] in LAYERS else None


def test_every_module_belongs_to_a_layer(imports: dict[str, set[str]]) -> None:
    loose = sorted(
        m for m in imports if layer_of(m) is None and m not in ("egosim", "egosim.__main__")
    )
    assert loose == [], f"modules outside the layers of docs/ARCHITECTURE.md: {loose}"


def test_imports_point_down_the_layers(imports: dict[str, set[str]]) -> None:
    upward = sorted(
        f"{module} -> {imported}"
        for module, targets in imports.items()
        for imported in targets
        if (here := layer_of(module)) is not None
        and (there := layer_of(imported)) is not None
        and LAYERS.index(there) < LAYERS.index(here)
    )
    assert upward == [], "imports that run up a layer:\n" + "\n".join(upward)


def test_the_pure_core_and_the_ros_side_do_not_know_each_other(
    imports: dict[str, set[str]],
) -> None:
    crossing = sorted(
        f"{module} -> {imported}"
        for module, targets in imports.items()
        for imported in targets
        if (layer_of(module) in PURE and layer_of(imported) in ROS_SIDE)
        or (layer_of(module) in ROS_SIDE and layer_of(imported) in PURE)
    )
    assert crossing == [], "imports between the pure core and ROS:\n" + "\n".join(crossing)


def in_package(module: str, package: str) -> bool:
    return module == package or module.startswith(package + ".")


def test_the_bridge_protocol_storey_stands_on_nothing_above_it(
    imports: dict[str, set[str]],
) -> None:
    upward = sorted(
        f"{module} -> {imported}"
        for module, targets in imports.items()
        if in_package(module, BRIDGE_PROTOCOL)
        for imported in targets
        if in_package(imported, "egosim.bridge") and not in_package(imported, BRIDGE_PROTOCOL)
    )
    assert upward == [], "bridge/protocol/ imports the storey above it:\n" + "\n".join(upward)


def test_no_modules_import_each_other_in_a_circle(imports: dict[str, set[str]]) -> None:
    try:
        graphlib.TopologicalSorter(imports).prepare()
    except graphlib.CycleError as error:
        pytest.fail(f"import circle: {' -> '.join(error.args[1])}")
