"""JUnit XML for CI systems: one testcase per case; failed criteria are failures,
cases that could not be scored are errors, cases not run are skipped."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

from egosim.batch.documents import CaseResult, ResultsDocument
from egosim.batch.logs import tail_report

JUNIT_FILE = "junit.xml"


def _wall_s(case: CaseResult) -> float:
    timings = case.get("timings")
    return 0.0 if timings is None else timings["case_wall_s"]


def junit_xml(suite_name: str, document: ResultsDocument) -> ET.ElementTree:
    cases = document["cases"]
    counts = document["summary"]
    total_time = sum(_wall_s(c) for c in cases)
    suite = ET.Element(
        "testsuite",
        name=suite_name,
        tests=str(counts["cases"]),
        failures=str(counts["failed"]),
        errors=str(counts["errors"]),
        skipped=str(counts["not_run"]),
        time=f"{total_time:.3f}",
    )
    for case in cases:
        element = ET.SubElement(
            suite, "testcase", classname=suite_name, name=case["name"], time=f"{_wall_s(case):.3f}"
        )
        status = case["status"]
        if status == "failed":
            failure = ET.SubElement(element, "failure", message=case["reason"], type="criteria")
            failure.text = _details(case)
        elif status == "error":
            error = ET.SubElement(element, "error", message=case["reason"], type="case")
            error.text = _details(case)
        elif status == "not_run":
            ET.SubElement(element, "skipped", message="the batch stopped before this case")
        if case.get("folder"):
            out = ET.SubElement(element, "system-out")
            out.text = f"case folder: {case['folder']}; bag: {case.get('bag')}"
    ET.indent(suite)
    return ET.ElementTree(suite)


def _details(case: CaseResult) -> str:
    lines = [f"reason: {case['reason']}", f"end: {case.get('end')}"]
    for infraction in case.get("infractions") or []:
        lines.append(
            f"{infraction['time_s']:.2f} s  {infraction['kind']}  at "
            f"({infraction['x']:.1f}, {infraction['y']:.1f})  {infraction['detail']}"
        )
    lines.extend(tail_report(case.get("log_tail")))
    return "\n".join(lines)


def write_junit(out_dir: Path, suite_name: str, document: ResultsDocument) -> Path:
    path = out_dir / JUNIT_FILE
    junit_xml(suite_name, document).write(path, encoding="utf-8", xml_declaration=True)
    return path
