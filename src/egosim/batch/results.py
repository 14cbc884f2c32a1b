"""results.json: every case's result in suite order, with a summary.

Wall-clock figures live under "execution" (the whole run) and each case's "timings", so
two runs of a deterministic suite differ in those keys only.
"""

from __future__ import annotations

import json
from collections import Counter
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Final, cast

from egosim import __version__
from egosim.batch.case import CaseSpec
from egosim.batch.case_runner import PASSED
from egosim.batch.documents import CaseResult, Execution, ResultsDocument, Summary
from egosim.json_value import JsonValue

RESULTS_FILE = "results.json"
NOT_RUN: Final = "not_run"


def summary(results: Iterable[CaseResult]) -> Summary:
    counts = Counter(result["status"] for result in results)
    return {
        "cases": sum(counts.values()),
        "passed": counts["passed"],
        "failed": counts["failed"],
        "errors": counts["error"],
        "not_run": counts[NOT_RUN],
    }


def not_run(case: CaseSpec) -> CaseResult:
    """The result of a case the batch was stopped before running."""
    return {"name": case.name, "parameters": case.parameters, "status": NOT_RUN, "reason": ""}


def results_document(
    suite: Path,
    cases: Sequence[CaseSpec],
    results: dict[str, CaseResult],
    execution: Execution,
) -> ResultsDocument:
    """The document: `results` (by case name) in suite order; cases without one not run."""
    ordered = [results.get(case.name) or not_run(case) for case in cases]
    return {
        "suite": suite.name,
        "egosim_version": __version__,
        "summary": summary(ordered),
        "cases": ordered,
        "execution": execution,
    }


def write_results(out_dir: Path, document: ResultsDocument) -> Path:
    path = out_dir / RESULTS_FILE
    path.write_text(json.dumps(document, indent=1) + "\n", encoding="utf-8")
    return path


def previous_results(out_dir: Path) -> dict[str, CaseResult]:
    """The results of an earlier run in `out_dir`, by case name ({} if none)."""
    try:
        document: JsonValue = json.loads((out_dir / RESULTS_FILE).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    cases = document.get("cases") if isinstance(document, dict) else None
    if not isinstance(cases, list):
        return {}
    # Entries as write_results wrote them (one without a name and status is passed over).
    return {
        name: cast(CaseResult, result)
        for result in cases
        if isinstance(result, dict)
        and isinstance(name := result.get("name"), str)
        and isinstance(result.get("status"), str)
    }


def needs_rerun(result: CaseResult | None) -> bool:
    """A case to run again with --rerun-failed: anything but a pass."""
    return result is None or result["status"] != PASSED
