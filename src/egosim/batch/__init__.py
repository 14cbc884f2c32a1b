"""`egosim batch`: a stack run through many scenario cases, each scored from the world.

Modules (imported one by one: a case's simulator loads only what it needs):
    suite        load_suite: suite files (suite.schema.json) -> concrete CaseSpecs
    sweep        parameter lists, ranges and products; stable case names
    case         CaseSpec, StackSpec: one case as picklable data
    simulate     a case's simulator process (`python -m egosim.batch.simulate DIR`)
    case_runner  run_case: one case's processes, supervised -> its result
    pool         run_local (N cases at a time) and run_ray (one Ray task per case)
    results, junit, html_report   results.json, junit.xml, report.html
"""
