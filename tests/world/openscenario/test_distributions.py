"""ParameterValueDistribution files: deterministic sets and value sets combine in file
order; every stochastic distribution draws inside its support, the same seed the same
cases."""

from __future__ import annotations

import statistics

import pytest

from egosim.world.openscenario import read_distribution
from egosim.world.scenario import ScenarioError


def distribution(body: str) -> str:
    return f"""<?xml version="1.0"?><OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" author="t" description="d"/>
  <ParameterValueDistribution><ScenarioFile filepath="cut_in.xosc"/>{body}
  </ParameterValueDistribution></OpenSCENARIO>"""


def test_value_sets_go_together_and_combine_with_the_single_parameters() -> None:
    text = distribution("""<Deterministic>
      <DeterministicMultiParameterDistribution><ValueSetDistribution>
        <ParameterValueSet><ParameterAssignment parameterRef="EgoSpeed" value="20"/>
          <ParameterAssignment parameterRef="CutInSpeed" value="25"/></ParameterValueSet>
        <ParameterValueSet><ParameterAssignment parameterRef="EgoSpeed" value="30"/>
          <ParameterAssignment parameterRef="CutInSpeed" value="33"/></ParameterValueSet>
      </ValueSetDistribution></DeterministicMultiParameterDistribution>
      <DeterministicSingleParameterDistribution parameterName="CutInGap">
        <DistributionRange stepWidth="0.5"><Range lowerLimit="10" upperLimit="11"/>
        </DistributionRange></DeterministicSingleParameterDistribution>
    </Deterministic>""")
    read = read_distribution(text, "d.xosc")
    assert read.scenario_file == "cut_in.xosc"
    assert read.cases == tuple(
        {"EgoSpeed": ego, "CutInSpeed": cut_in, "CutInGap": gap}
        for ego, cut_in in (("20", "25"), ("30", "33"))
        for gap in ("10", "10.5", "11")
    )


STOCHASTIC = """<Stochastic numberOfTestRuns="400" randomSeed="{seed}">
  <StochasticDistribution parameterName="Normal">
    <NormalDistribution expectedValue="4" variance="1"/></StochasticDistribution>
  <StochasticDistribution parameterName="CutNormal">
    <NormalDistribution expectedValue="4" variance="4"><Range lowerLimit="3" upperLimit="5"/>
    </NormalDistribution></StochasticDistribution>
  <StochasticDistribution parameterName="LogNormal">
    <LogNormalDistribution expectedValue="0" variance="0.25"/></StochasticDistribution>
  <StochasticDistribution parameterName="Uniform">
    <UniformDistribution><Range lowerLimit="8" upperLimit="20"/></UniformDistribution>
  </StochasticDistribution>
  <StochasticDistribution parameterName="Poisson">
    <PoissonDistribution expectedValue="3"/></StochasticDistribution>
  <StochasticDistribution parameterName="Histogram"><HistogramDistribution>
    <Bin weight="3"><Range lowerLimit="0" upperLimit="1"/></Bin>
    <Bin weight="1"><Range lowerLimit="10" upperLimit="11"/></Bin>
  </HistogramDistribution></StochasticDistribution>
  <StochasticDistribution parameterName="Choice"><ProbabilityDistributionSet>
    <Element value="wet" weight="1"/><Element value="dry" weight="3"/>
  </ProbabilityDistributionSet></StochasticDistribution>
</Stochastic>"""


def draws(seed: int = 7) -> dict[str, list[str]]:
    cases = read_distribution(distribution(STOCHASTIC.format(seed=seed)), "s.xosc").cases
    assert len(cases) == 400
    return {name: [case[name] for case in cases] for name in cases[0]}


def test_every_stochastic_distribution_draws_inside_its_support() -> None:
    drawn = draws()
    numbers = {
        name: [float(v) for v in values] for name, values in drawn.items() if name != "Choice"
    }
    # Fixed seed: these are the same 400 draws every time, so the bounds are exact checks.
    assert statistics.fmean(numbers["Normal"]) == pytest.approx(4.0, abs=0.2)
    assert all(3.0 <= v <= 5.0 for v in numbers["CutNormal"])
    assert all(v > 0.0 for v in numbers["LogNormal"])
    assert statistics.median(numbers["LogNormal"]) == pytest.approx(1.0, abs=0.1)  # e^0
    assert all(8.0 <= v <= 20.0 for v in numbers["Uniform"])
    assert all(v == int(v) and v >= 0 for v in numbers["Poisson"])
    assert statistics.fmean(numbers["Poisson"]) == pytest.approx(3.0, abs=0.3)
    assert all(0.0 <= v <= 1.0 or 10.0 <= v <= 11.0 for v in numbers["Histogram"])
    low_bin = sum(v <= 1.0 for v in numbers["Histogram"]) / 400
    assert low_bin == pytest.approx(0.75, abs=0.07)  # weights 3 : 1
    assert set(drawn["Choice"]) == {"wet", "dry"}
    assert drawn["Choice"].count("dry") / 400 == pytest.approx(0.75, abs=0.07)


def test_the_same_seed_gives_the_same_cases_another_seed_others() -> None:
    assert draws(7) == draws(7)
    assert draws(7)["Uniform"] != draws(8)["Uniform"]


def test_a_range_no_draw_can_meet_is_an_error_not_a_hang() -> None:
    impossible = """<Stochastic numberOfTestRuns="1"><StochasticDistribution parameterName="P">
      <PoissonDistribution expectedValue="3"><Range lowerLimit="0.2" upperLimit="0.8"/>
      </PoissonDistribution></StochasticDistribution></Stochastic>"""
    with pytest.raises(ScenarioError, match="draws nothing inside its Range"):
        read_distribution(distribution(impossible), "s.xosc")
