"""`egosim batch`: a stack run through many scenario cases, each scored from the world.

Modules (imported one by one: a case's simulator loads only what it needs):
    suite        load_suite: suite files (suite.schema.json) -> concrete CaseSpecs
    sweep        parameter lists, ranges and products; stable case names
    case         CaseSpec, StackSpec: one case as picklable data
    simulate     a case's simulator: its master, `egosim run`, the drive's evaluation
    worker       the simulator worker process (`python -m egosim.batch.worker`): one case
                 after another, nothing carried over; worker_protocol: its lines
    warm_simulator  the supervisor's handle on a worker, kept warm from case to case;
                 early_workers: workers started as the batch command begins
    case_runner  run_case: one case's master, stack and simulator, supervised -> its
                 result (start_case, drive_case, EndingCase: the same in parts)
    pool         run_local (N slots) and run_ray (one Ray actor per slot); interrupt:
                 stopping a batch (once: in order; twice: at once); local_slot: a local
                 slot's cases overlapping at their ends
    results, junit, html_report   results.json, junit.xml, report.html
"""
