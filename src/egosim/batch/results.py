"""results.json: every case's result in suite order, with a summary.

Wall-clock figures live under "execution" (the whole run) and each case's "timings", so
two runs of a deterministic suite differ in those keys only.
"""

from __future__ import annotations

import json
from collections import Counter
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

from egosim import __version__
from egosim.batch.case import CaseSpec
from egosim.batch.case_runner import PASSED

RESULTS_FILE = "results.json"
NOT_RUN = "not_run"


def summary(results: Iterable[dict[str, Any]]) -> dict[str, int]:
    counts = Counter(result["status"] for result in results)
    return {
        "cases": sum(counts.values()),
        "passed": counts["passed"],
        "failed": counts["failed"],
        "errors": counts["error"],
        "not_run": counts[NOT_RUN],
    }


def not_run(case: CaseSpec) -> dict[str, Any]:
    """The result of a case the batch was stopped before running."""
    return {"name": case.name, "parameters": case.parameters, "status": NOT_RUN, "reason": ""}


def results_document(
    suite: Path,
    cases: Sequence[CaseSpec],
    results: dict[str, dict[str, Any]],
    execution: dict[str, Any],
) -> dict[str, Any]:
    """The document: `results` (by case name) in suite order; cases without one not run."""
    ordered = [results.get(case.name) or not_run(case) for case in cases]
    return {
        "suite": suite.name,
        "egosim_version": __version__,
        "summary": summary(ordered),
        "cases": ordered,
        "execution": execution,
    }


def write_results(out_dir: Path, document: dict[str, Any]) -> Path:
    path = out_dir / RESULTS_FILE
    path.write_text(json.dumps(document, indent=1) + "\n", encoding="utf-8")
    return path


def previous_results(out_dir: Path) -> dict[str, dict[str, Any]]:
    """The results of an earlier run in `out_dir`, by case name ({} if none)."""
    try:
        document = json.loads((out_dir / RESULTS_FILE).read_text(encoding="utf-8"))
        return {result["name"]: result for result in document["cases"]}
    except (OSError, ValueError, KeyError, TypeError):
        return {}


def needs_rerun(result: dict[str, Any] | None) -> bool:
    """A case to run again with --rerun-failed: anything but a pass."""
    return result is None or result["status"] != PASSED
