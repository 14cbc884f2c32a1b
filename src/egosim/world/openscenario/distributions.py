"""ParameterValueDistribution files: the concrete parameter sets of a logical scenario.

Deterministic: each DeterministicSingleParameterDistribution gives one parameter its
values (a DistributionSet's elements, a DistributionRange from lowerLimit to upperLimit
in stepWidth steps), each DeterministicMultiParameterDistribution gives several
parameters values together (ParameterValueSets); the cases are every combination of
them, in file order. Stochastic: numberOfTestRuns draws with randomSeed (0 when none)
from each parameter's distribution: Normal (variance, optionally cut to a Range),
LogNormal, Uniform (a Range), Poisson, Histogram (bins of ranges with weights) and
ProbabilityDistributionSet (values with weights). The same file and seed give the same
cases.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from egosim.world.openscenario.parameters import Scope, text_of
from egosim.world.openscenario.read_conditions import UnsupportedElementError
from egosim.world.openscenario.reading import Element
from egosim.world.openscenario.xmltree import Node, parse_xml

MAX_CASES = 100_000
_RANGE_STEPS_EPS = 1e-9


@dataclass(frozen=True)
class Distribution:
    """The scenario file a distribution varies (as written, relative to the
    distribution's file) and its concrete parameter sets, each name -> value text."""

    scenario_file: str
    cases: tuple[dict[str, str], ...]


def is_distribution(root: Node) -> bool:
    return root.child("ParameterValueDistribution") is not None


def read_distribution(text: str | bytes, label: str) -> Distribution:
    root = parse_xml(text, label)
    node = root.child("ParameterValueDistribution")
    if node is None:
        raise root.error("holds no <ParameterValueDistribution>")
    element = Element(node, Scope())
    scenario = element.require("ScenarioFile").text("filepath")
    deterministic = element.child("Deterministic")
    stochastic = element.child("Stochastic")
    if deterministic is not None:
        cases = _deterministic(deterministic)
    elif stochastic is not None:
        cases = _stochastic(stochastic)
    else:
        raise node.error("needs a <Deterministic> or <Stochastic> distribution")
    return Distribution(scenario, tuple(cases))


def _number_text(value: float) -> str:
    return text_of(round(value, 12))


def _range(element: Element) -> tuple[float, float]:
    limits = element.require("Range")
    return limits.number("lowerLimit"), limits.number("upperLimit")


def _single_values(element: Element) -> list[str]:
    choice = element.only_child()
    if choice is None:
        raise element.node.error("gives no values")
    if choice.tag == "DistributionSet":
        return [e.text("value") for e in choice.children("Element")]
    if choice.tag == "DistributionRange":
        low, high = _range(choice)
        step = choice.number("stepWidth")
        if step <= 0:
            raise choice.node.error("stepWidth must be positive")
        count = math.floor((high - low) / step + _RANGE_STEPS_EPS) + 1
        if count > MAX_CASES:
            raise choice.node.error(f"gives {count} values (at most {MAX_CASES})")
        return [_number_text(low + k * step) for k in range(count)]
    raise UnsupportedElementError(choice.node, "is not a deterministic distribution egosim reads")


def _deterministic(element: Element) -> list[dict[str, str]]:
    axes: list[list[dict[str, str]]] = []
    for part in element.children():
        if part.tag == "DeterministicSingleParameterDistribution":
            name = part.text("parameterName")
            axes.append([{name: value} for value in _single_values(part)])
        elif part.tag == "DeterministicMultiParameterDistribution":
            sets = part.require("ValueSetDistribution").children("ParameterValueSet")
            axes.append(
                [
                    {
                        a.text("parameterRef"): a.text("value")
                        for a in s.children("ParameterAssignment")
                    }
                    for s in sets
                ]
            )
        else:
            raise UnsupportedElementError(part.node, "is not a deterministic distribution")
    if math.prod(len(axis) for axis in axes) > MAX_CASES:
        raise element.node.error(f"gives more than {MAX_CASES} cases")
    cases = []
    for combination in itertools.product(*axes):
        case: dict[str, str] = {}
        for values in combination:
            case.update(values)
        cases.append(case)
    return cases


def _draw(element: Element, rng: np.random.Generator) -> float | str:
    choice = element.only_child()
    if choice is None:
        raise element.node.error("gives no distribution")
    tag = choice.tag
    limits = _range(choice) if choice.child("Range") is not None else None
    if tag == "UniformDistribution":
        assert limits is not None
        return float(rng.uniform(*limits))
    if tag == "ProbabilityDistributionSet":
        elements = choice.children("Element")
        weights = np.array([e.number("weight") for e in elements])
        k = int(rng.choice(len(elements), p=weights / weights.sum()))
        return elements[k].text("value")
    if tag == "HistogramDistribution":
        bins = choice.children("Bin")
        weights = np.array([b.number("weight") for b in bins])
        k = int(rng.choice(len(bins), p=weights / weights.sum()))
        return float(rng.uniform(*_range(bins[k])))
    draw: float
    for _ in range(1000):
        if tag == "NormalDistribution":
            draw = float(
                rng.normal(choice.number("expectedValue"), math.sqrt(choice.number("variance")))
            )
        elif tag == "LogNormalDistribution":
            draw = float(
                rng.lognormal(choice.number("expectedValue"), math.sqrt(choice.number("variance")))
            )
        elif tag == "PoissonDistribution":
            draw = float(rng.poisson(choice.number("expectedValue")))
        else:
            raise UnsupportedElementError(
                choice.node, "is not a stochastic distribution egosim reads"
            )
        if limits is None or limits[0] <= draw <= limits[1]:
            return draw
    raise choice.node.error("draws nothing inside its Range")


def _stochastic(element: Element) -> list[dict[str, str]]:
    runs = element.integer("numberOfTestRuns")
    if not 0 < runs <= MAX_CASES:
        raise element.node.error(f"numberOfTestRuns must be 1..{MAX_CASES}")
    rng = np.random.default_rng(element.integer("randomSeed", 0))
    parts = element.children("StochasticDistribution")
    cases = []
    for _ in range(runs):
        case = {}
        for part in parts:
            value = _draw(part, rng)
            # Six significant digits: values (and the case names made of them) stay legible.
            case[part.text("parameterName")] = (
                value if isinstance(value, str) else format(value, ".6g")
            )
        cases.append(case)
    return cases
