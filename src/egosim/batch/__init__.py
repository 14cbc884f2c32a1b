"""`egosim batch`: a stack run through many scenario cases, each scored from the world.

Public API:
    load_suite, suite_schema, SuiteError       suite files -> concrete cases
    CaseSpec, StackSpec                        one case, as picklable data
    run_case                                   one case in its own processes -> its result
    run_local, run_ray                         many cases (thread-supervised pool or Ray)
    results_document, write_results, write_junit, write_html_report   outputs
"""

from egosim.batch.case import CaseSpec, StackSpec
from egosim.batch.case_runner import run_case
from egosim.batch.errors import SuiteError
from egosim.batch.html_report import write_html_report
from egosim.batch.junit import write_junit
from egosim.batch.pool import run_local, run_ray
from egosim.batch.results import results_document, write_results
from egosim.batch.suite import load_suite, suite_schema

__all__ = [
    "CaseSpec",
    "StackSpec",
    "SuiteError",
    "load_suite",
    "results_document",
    "run_case",
    "run_local",
    "run_ray",
    "suite_schema",
    "write_html_report",
    "write_junit",
    "write_results",
]
