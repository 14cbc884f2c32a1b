"""JUnit XML for CI systems: one testcase per case; failed criteria are failures,
cases that could not be scored are errors, cases not run are skipped."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

from egosim.batch.logs import tail_report

JUNIT_FILE = "junit.xml"


def junit_xml(suite_name: str, document: dict[str, Any]) -> ET.ElementTree:
    cases = document["cases"]
    counts = document["summary"]
    total_time = sum((c.get("timings") or {}).get("case_wall_s") or 0.0 for c in cases)
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
        wall = (case.get("timings") or {}).get("case_wall_s") or 0.0
        element = ET.SubElement(
            suite, "testcase", classname=suite_name, name=case["name"], time=f"{wall:.3f}"
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


def _details(case: dict[str, Any]) -> str:
    lines = [f"reason: {case['reason']}", f"end: {case.get('end')}"]
    for infraction in case.get("infractions") or []:
        lines.append(
            f"{infraction['time_s']:.2f} s  {infraction['kind']}  at "
            f"({infraction['x']:.1f}, {infraction['y']:.1f})  {infraction['detail']}"
        )
    lines.extend(tail_report(case.get("log_tail")))
    return "\n".join(lines)


def write_junit(out_dir: Path, suite_name: str, document: dict[str, Any]) -> Path:
    path = out_dir / JUNIT_FILE
    junit_xml(suite_name, document).write(path, encoding="utf-8", xml_declaration=True)
    return path
