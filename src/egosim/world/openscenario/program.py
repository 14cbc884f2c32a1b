"""An OpenSCENARIO file read: its parameters, catalogues, entities and storyboard, ready
to start on a world.

Reading checks everything once (a mistake is a ScenarioError naming file, line and
element; several at once are listed together) and collects a note for each element
egosim reads but does not carry out. Each start reads the storyboard afresh from the
parsed document, so every run begins with new element states.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from functools import partial

from egosim.world.openscenario.actions import NoteAction
from egosim.world.openscenario.catalogs import Catalogs, catalog_directories
from egosim.world.openscenario.conditions import Trigger
from egosim.world.openscenario.engine import Evaluation, ScenarioRun
from egosim.world.openscenario.entities import EntityDefinition, EntityKind, VehicleFigures
from egosim.world.openscenario.expressions import Value
from egosim.world.openscenario.parameters import Scope, declare
from egosim.world.openscenario.read_actions import (
    global_action,
    is_external_controller,
    private_action,
)
from egosim.world.openscenario.read_conditions import UnsupportedElementError, condition, trigger
from egosim.world.openscenario.reading import Element
from egosim.world.openscenario.signal_controllers import Phase, SignalController, start_times
from egosim.world.openscenario.signal_states import parse_state
from egosim.world.openscenario.storyboard import (
    ActElement,
    Action,
    ActionElement,
    EventElement,
    ManeuverElement,
    ManeuverGroupElement,
    Storyboard,
    StoryElement,
)
from egosim.world.openscenario.xmltree import Node, parse_xml
from egosim.world.scenario.errors import ScenarioError
from egosim.world.scenario.model import StoryboardWorld
from egosim.yamltext import Problems

EGO_NAMES = ("ego", "hero", "ego_vehicle", "egovehicle")
"""Names that make an entity the ego (case-insensitive) when none has an external
controller: MORAI's and esmini's "Ego", CARLA's "hero"."""
PRIORITIES = ("override", "overwrite", "skip", "parallel")
_KINDS = {
    "Vehicle": EntityKind.VEHICLE,
    "Pedestrian": EntityKind.PEDESTRIAN,
    "MiscObject": EntityKind.MISC_OBJECT,
}


def version_of(root: Node) -> tuple[int, int]:
    header = root.child("FileHeader")
    if header is None:
        raise root.error("needs a <FileHeader>")
    try:
        return int(header.get("revMajor") or 1), int(header.get("revMinor") or 0)
    except ValueError:
        raise header.error("revMajor and revMinor must be whole numbers") from None


def root_of(text: str | bytes, label: str) -> Node:
    root = parse_xml(text, label)
    if root.tag != "OpenSCENARIO":
        raise root.error("is not an OpenSCENARIO document (its root must be <OpenSCENARIO>)")
    return root


def map_reference(root: Node, scope: Scope | None = None) -> str:
    """The map a scenario runs on: <RoadNetwork><LogicFile filepath> (a parameter may
    give it)."""
    network = root.child("RoadNetwork")
    logic = None if network is None else network.child("LogicFile")
    if logic is None or not logic.get("filepath"):
        raise root.error("names no map: <RoadNetwork><LogicFile filepath> is missing")
    return Element(logic, scope or Scope()).text("filepath")


class Reader:
    """Reads one scenario's elements in the scenario's parameter scope."""

    def __init__(self, root: Node, scope: Scope, catalogs: Catalogs, notes: list[str]) -> None:
        self.root = root
        self.scope = scope
        self.catalogs = catalogs
        self.notes = notes

    def entry(self, reference: Element) -> Element:
        return self.catalogs.resolve(reference, self.scope)

    def element(self, node: Node) -> Element:
        return Element(node, self.scope)

    # -- entities ------------------------------------------------------------------

    def entities(self, problems: Problems) -> list[EntityDefinition]:
        found: list[EntityDefinition] = []
        section = self.root.child("Entities")
        if section is None:
            return found
        for node in section.children():
            if node.tag == "EntitySelection":
                self.notes.append(node.note("is not used: conditions name entities one by one"))
                continue
            with problems.collecting():
                definition = self._entity(self.element(node))
                if definition is not None:
                    found.append(definition)
        return found

    def _entity(self, element: Element) -> EntityDefinition | None:
        name = element.text("name")
        body = None
        for child in element.children():
            if child.tag == "CatalogReference":
                body = self.entry(child)
            elif child.tag in _KINDS:
                body = child
        if body is None:
            self.notes.append(
                element.node.note(f"{name!r}: no Vehicle, Pedestrian or MiscObject; left out")
            )
            return None
        kind = _KINDS.get(body.tag)
        if kind is None:
            raise body.node.error(
                f"entity {name!r}: a catalogue entry of kind <{body.tag}> is not an object"
            )
        box = body.require("BoundingBox")
        centre = box.require("Center")
        size = box.require("Dimensions")
        performance = body.child("Performance")
        external = False
        controller_holder = element.child("ObjectController")
        if controller_holder is not None:
            controller = controller_holder.child("Controller")
            reference = controller_holder.child("CatalogReference")
            if controller is None and reference is not None:
                controller = self.entry(reference)
            external = controller is not None and is_external_controller(controller)
        category_attribute = {
            EntityKind.VEHICLE: "vehicleCategory",
            EntityKind.PEDESTRIAN: "pedestrianCategory",
            EntityKind.MISC_OBJECT: "miscObjectCategory",
        }[kind]
        properties = body.child("Properties")
        inf = float("inf")
        axles = body.child("Axles") if kind is EntityKind.VEHICLE else None
        return EntityDefinition(
            name=name,
            kind=kind,
            model=body.text("name", body.text("model", name)),
            category=body.text(category_attribute, ""),
            length=size.number("length"),
            width=size.number("width"),
            height=size.number("height"),
            centre=(centre.number("x"), centre.number("y"), centre.number("z")),
            max_speed=performance.number("maxSpeed", inf, finite=False) if performance else inf,
            max_acceleration=performance.number("maxAcceleration", inf, finite=False)
            if performance
            else inf,
            max_deceleration=performance.number("maxDeceleration", inf, finite=False)
            if performance
            else inf,
            external=external,
            properties=tuple(
                (p.text("name", ""), p.text("value", ""))
                for p in (properties.children("Property") if properties else [])
            ),
            figures=None if axles is None else _figures(body, axles),
        )

    # -- traffic signal controllers ----------------------------------------------------

    def signal_controllers(self, problems: Problems) -> dict[str, SignalController]:
        """RoadNetwork's TrafficSignalControllers, by name."""
        found: dict[str, SignalController] = {}
        network = self.root.child("RoadNetwork")
        signals = None if network is None else network.child("TrafficSignals")
        for node in signals.children("TrafficSignalController") if signals is not None else []:
            with problems.collecting():
                controller = self._signal_controller(self.element(node))
                if controller.name in found:
                    raise node.error(f"a second controller named {controller.name!r}")
                found[controller.name] = controller
        self.notes.extend(start_times(found))
        return found

    def _signal_controller(self, element: Element) -> SignalController:
        phases = []
        for phase in element.children("Phase"):
            duration = phase.number("duration")
            if duration < 0.0 or duration == float("inf"):
                raise phase.node.error(f"duration {duration} is not a time")
            states = []
            for state in phase.children("TrafficSignalState"):
                light = state.text("trafficSignalId")
                aspect = parse_state(state.text("state"))
                if aspect is None:
                    self.notes.append(
                        state.node.note(f"state {state.text('state')!r} is unknown; left out")
                    )
                    continue
                states.append((light, aspect))
            phases.append(Phase(phase.text("name"), duration, tuple(states)))
        delay = element.number("delay", 0.0)
        if delay < 0.0 or delay == float("inf"):
            raise element.node.error(f"delay {delay} is not a time")
        return SignalController(
            element.node,
            element.text("name"),
            tuple(phases),
            delay=delay,
            reference=element.text("reference", ""),
        )

    # -- storyboard ----------------------------------------------------------------

    def storyboard(self, problems: Problems) -> tuple[Storyboard, Evaluation]:
        board = Storyboard("storyboard", "storyboard")
        node = self.root.child("Storyboard")
        if node is None:
            raise self.root.error("needs a <Storyboard>")
        element = self.element(node)
        init = element.child("Init")
        if init is not None:
            actions = init.child("Actions")
            for child in actions.children() if actions is not None else []:
                with problems.collecting():
                    board.init.extend(self._init_actions(child))
        for story in element.children("Story"):
            with problems.collecting():
                board.stories.append(self._story(story, problems))
        board.stop_trigger = trigger(element.child("StopTrigger"), self, self.notes)
        evaluation_node = element.child("Evaluation") or self.element(self.root).child("Evaluation")
        evaluation = Evaluation(None, None)
        if evaluation_node is not None:
            evaluation = Evaluation(
                self._groups(evaluation_node, "SuccessConditionGroup"),
                self._groups(evaluation_node, "FailureConditionGroup"),
            )
        return board, evaluation

    def _groups(self, element: Element, tag: str) -> Trigger | None:
        """MORAI's evaluation groups (each one a group of conditions) as a trigger."""
        groups = element.children(tag)
        if not groups:
            return None
        return Trigger(
            [[condition(node, self) for node in group.children("Condition")] for group in groups]
        )

    def _action(self, element: Element, name: str) -> ActionElement:
        action = ActionElement("action", name)
        action.spec = self._spec(element.node, lambda: self._action_spec(element))
        return action

    def _spec(self, node: Node, read: Callable[[], Action]) -> Action:
        """The action `read` gives; an unsupported one becomes a note when it runs."""
        try:
            return read()
        except UnsupportedElementError as unsupported:
            self.notes.append(f"{unsupported}; left out")
            return NoteAction(node, "")

    def _action_spec(self, element: Element) -> Action:
        choice = element.only_child()
        if choice is None:
            raise element.node.error("holds no action")
        if choice.tag == "PrivateAction":
            return private_action(choice, self)
        if choice.tag == "GlobalAction":
            return global_action(choice, self)
        raise UnsupportedElementError(choice.node, "is not carried out by egosim")

    def _init_actions(self, element: Element) -> list[tuple[ActionElement, tuple[str, ...]]]:
        if element.tag == "Private":
            entity = element.text("entityRef")
            found: list[tuple[ActionElement, tuple[str, ...]]] = []
            for k, private in enumerate(element.children("PrivateAction")):
                action = ActionElement("action", f"Init:{entity}:{k}")
                action.spec = self._spec(private.node, partial(private_action, private, self, True))
                found.append((action, (entity,)))
            return found
        if element.tag == "GlobalAction":
            action = ActionElement("action", "Init:global")
            action.spec = self._spec(element.node, lambda: global_action(element, self))
            return [(action, ())]
        action = ActionElement("action", "Init:other")
        action.spec = NoteAction(element.node, f"<{element.tag}> is not carried out by egosim")
        return [(action, ())]

    def _story(self, element: Element, problems: Problems) -> StoryElement:
        declarations = element.child("ParameterDeclarations")
        reader = self
        if declarations is not None:
            scope = self.scope.child()
            declare(declarations.node, scope)
            reader = Reader(self.root, scope, self.catalogs, self.notes)
            element = element.with_scope(scope)
        story = StoryElement("story", element.text("name"))
        for act in element.children("Act"):
            with problems.collecting():
                story.acts.append(reader._act(act, problems))
        return story

    def _act(self, element: Element, problems: Problems) -> ActElement:
        act = ActElement("act", element.text("name"))
        act.start_trigger = trigger(element.child("StartTrigger"), self, self.notes)
        act.stop_trigger = trigger(element.child("StopTrigger"), self, self.notes)
        for group in element.children("ManeuverGroup"):
            with problems.collecting():
                act.groups.append(self._group(group, problems))
        return act

    def _group(self, element: Element, problems: Problems) -> ManeuverGroupElement:
        actors_element = element.require("Actors")
        actors = tuple(ref.text("entityRef") for ref in actors_element.children("EntityRef"))
        if actors_element.boolean("selectTriggeringEntities", False):
            self.notes.append(
                actors_element.node.note(
                    "selectTriggeringEntities is not supported: only the listed actors act"
                )
            )
        group = ManeuverGroupElement(
            "maneuverGroup",
            element.text("name"),
            actors=actors,
            maximum_executions=element.integer("maximumExecutionCount", 1),
        )
        for child in element.children():
            with problems.collecting():
                if child.tag == "Maneuver":
                    group.maneuvers.append(self._maneuver(child, problems))
                elif child.tag == "CatalogReference":
                    group.maneuvers.append(self._maneuver(self.entry(child), problems))
        return group

    def _maneuver(self, element: Element, problems: Problems) -> ManeuverElement:
        declarations = element.child("ParameterDeclarations")
        reader = self
        if declarations is not None and element.scope is self.scope:
            scope = self.scope.child()
            declare(declarations.node, scope)
            element = element.with_scope(scope)
        if element.scope is not self.scope:
            reader = Reader(self.root, element.scope, self.catalogs, self.notes)
        maneuver = ManeuverElement("maneuver", element.text("name"))
        for event in element.children("Event"):
            with problems.collecting():
                maneuver.events.append(reader._event(event))
        return maneuver

    def _event(self, element: Element) -> EventElement:
        priority = element.choice("priority", PRIORITIES, "override")
        event = EventElement(
            "event",
            element.text("name"),
            priority=priority,
            maximum_executions=element.integer("maximumExecutionCount", 1),
            start_trigger=trigger(element.child("StartTrigger"), self, self.notes),
        )
        for action in element.children("Action"):
            event.actions.append(self._action(action, action.text("name", "")))
        if not event.actions:
            raise element.node.error("has no <Action>")
        return event


@dataclass
class OpenScenario:
    """A read OpenSCENARIO file; `start` runs it on a world (StoryboardProgram)."""

    label: str
    version: tuple[int, int]
    map_reference: str
    entities: tuple[EntityDefinition, ...]
    ego: str | None
    parameters: dict[str, Value]
    variables: dict[str, Value]
    notes: tuple[str, ...]
    _root: Node = field(repr=False)
    _scope: Scope = field(repr=False)
    _catalogs: Catalogs = field(repr=False)

    def start(
        self, world: StoryboardWorld, load_ego: bool, kinds: frozenset[str], drives_ego: bool
    ) -> ScenarioRun:
        notes: list[str] = []
        reader = Reader(self._root, self._scope, self._catalogs, notes)
        problems = Problems()
        board, evaluation = reader.storyboard(problems)
        controllers = reader.signal_controllers(problems)
        problems.raise_any()
        return ScenarioRun(
            world,
            board,
            evaluation,
            controllers,
            list(self.entities),
            self.ego,
            dict(self.parameters),
            dict(self.variables),
            load_ego,
            kinds,
            drives_ego,
        )


def _figures(vehicle: Element, axles: Element) -> VehicleFigures:
    front, rear = axles.require("FrontAxle"), axles.require("RearAxle")
    return VehicleFigures(
        front_axle_x=front.number("positionX"),
        rear_axle_x=rear.number("positionX"),
        wheel_diameter=front.number("wheelDiameter"),
        track_width=front.number("trackWidth"),
        max_steering=front.number("maxSteering"),
        mass=vehicle.optional_number("mass"),
    )


def choose_ego(definitions: list[EntityDefinition]) -> str | None:
    """The entity egosim's main ego plays: one with an external controller, else one
    named Ego / hero, else the first vehicle."""
    for definition in definitions:
        if definition.external:
            return definition.name
    for definition in definitions:
        if definition.name.lower() in EGO_NAMES:
            return definition.name
    for definition in definitions:
        if definition.kind is EntityKind.VEHICLE:
            return definition.name
    return None


def read_openscenario(
    text: str | bytes,
    label: str,
    catalog_files: Iterable[tuple[str, str | bytes]] = (),
    parameters: Mapping[str, str] | None = None,
) -> OpenScenario:
    """An OpenSCENARIO scenario from its text and its catalogue files' texts;
    `parameters` replace declared values (names that are not declared are an error)."""
    root = root_of(text, label)
    version = version_of(root)
    if root.child("ParameterValueDistribution") is not None:
        raise root.error("is a ParameterValueDistribution: run it with `egosim batch`")
    notes: list[str] = []
    if version[0] != 1 or version[1] > 3:
        notes.append(f"{label}: OpenSCENARIO {version[0]}.{version[1]} is read as 1.3")
    scope = Scope()
    problems = Problems()
    with problems.collecting():
        declare(root.child("ParameterDeclarations"), scope, parameters)
    problems.raise_any()
    variables = Scope()
    with problems.collecting():
        declare(
            root.child("VariableDeclarations"),
            variables,
            tag="VariableDeclaration",
            type_attribute="variableType",
        )
    catalogs = Catalogs(catalog_files, notes)
    reader = Reader(root, scope, catalogs, notes)
    reference = ""
    with problems.collecting():
        reference = map_reference(root, scope)
    definitions = reader.entities(problems)
    _, _ = reader.storyboard(problems)
    reader.signal_controllers(problems)
    problems.raise_any()
    for node in root.walk():
        if node.tag in _UNREAD:
            notes.append(node.note(_UNREAD[node.tag]))
    return OpenScenario(
        label,
        version,
        reference,
        tuple(definitions),
        choose_ego(definitions),
        dict(scope.values),
        dict(variables.values),
        tuple(dict.fromkeys(notes)),
        root,
        scope,
        catalogs,
    )


_UNREAD = {
    "SceneGraphFile": "is not loaded: egosim draws the map from its lanes",
    "MonitorDeclarations": "is not evaluated: egosim keeps no monitors",
    "Trailer": "is not simulated: egosim's vehicles pull no trailers",
    "TrailerHitch": "is not simulated: egosim's vehicles pull no trailers",
    "TrailerCoupler": "is not simulated: egosim's vehicles pull no trailers",
}


__all__ = ["OpenScenario", "ScenarioError", "catalog_directories", "read_openscenario"]
