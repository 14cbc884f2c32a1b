"""Running many cases: a local pool of N cases at a time, or one Ray task per case.

Each case is its own processes (simulator and stack, see case_runner), so the local pool
only supervises: N threads, each waiting on one case. Ctrl-C stops every running case's
processes (their scores so far are kept) and the cases not started are reported not run,
in the local pool and on Ray alike.
"""

from __future__ import annotations

import importlib
import os
import threading
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, wait
from typing import Any

from egosim.batch.case import CaseSpec
from egosim.batch.case_runner import ERROR, PASSED, run_case

Result = dict[str, Any]
OnResult = Callable[[Result, int], None]
"""Called with each finished case's result and the number of cases still running."""

RAY_POLL_S = 0.5


def default_workers() -> int:
    return max(len(os.sched_getaffinity(0)), 1)


def run_local(
    cases: Sequence[CaseSpec],
    out_dir: str,
    workers: int,
    on_result: OnResult,
    results: dict[str, Result] | None = None,
) -> dict[str, Result]:
    """Run `cases`, `workers` at a time; their results by name, also put in `results` as
    they come (so an interrupted run, which raises KeyboardInterrupt, leaves them there)."""
    cancel = threading.Event()
    results = {} if results is None else results
    executor = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="case")
    pending: set[Future[Result]] = {executor.submit(run_case, c, out_dir, cancel) for c in cases}
    try:
        while pending:
            done, pending = wait(pending, timeout=0.5, return_when=FIRST_COMPLETED)
            for future in done:
                result = future.result()
                results[result["name"]] = result
                on_result(result, sum(f.running() for f in pending))
    except KeyboardInterrupt:
        cancel.set()
        for future in pending:
            future.cancel()
        for future in pending:
            if not future.cancelled():
                result = future.result()
                results[result["name"]] = result
        raise
    finally:
        executor.shutdown(wait=True, cancel_futures=True)
    return results


def run_ray(
    cases: Sequence[CaseSpec],
    out_dir: str,
    address: str | None,
    on_result: OnResult,
    results: dict[str, Result] | None = None,
) -> dict[str, Result]:
    """One Ray task per case on the cluster at `address` (None: the one `ray start`
    left running on this machine, else a new local one); results as run_local's. The
    output folder must be on storage every node writes to."""
    ray = importlib.import_module("ray")  # an optional extra: pip install egosim[ray]
    ray.init(address=address, include_dashboard=False, log_to_driver=False)
    try:
        remote = ray.remote(num_cpus=1, max_retries=0)(run_cancellable_case)
        refs = {remote.remote(case, out_dir): case for case in cases}
        results = {} if results is None else results
        pending = list(refs)
        try:
            while pending:
                done, pending = ray.wait(pending, num_returns=1, timeout=RAY_POLL_S)
                for ref in done:
                    result = _ray_result(ray, ref, refs[ref])
                    if result is not None:
                        results[result["name"]] = result
                        on_result(result, len(pending))
        except KeyboardInterrupt:
            for ref in pending:
                ray.cancel(ref)
            for ref in pending:
                result = _ray_result(ray, ref, refs[ref])
                if result is not None:
                    results[result["name"]] = result
            raise
        return results
    finally:
        ray.shutdown()


def run_cancellable_case(case: CaseSpec, out_dir: str) -> Result:
    """run_case as a Ray task. Ray cancels a running task by raising KeyboardInterrupt in
    its thread wherever it is; here that only sets the case's cancel event, which the case
    watches as in the local pool, so it stops its processes in order and returns what it
    had driven. Cancelled before the case began, the task ends cancelled (not run)."""
    cancel, finished = threading.Event(), threading.Event()
    outcome: list[Result | BaseException] = []

    def work() -> None:
        try:
            outcome.append(run_case(case, out_dir, cancel))
        except BaseException as error:  # handed to the task, which raises it
            outcome.append(error)
        finally:
            finished.set()

    case_thread = threading.Thread(target=work, name="case")
    while True:
        try:
            if case_thread.ident is None:
                case_thread.start()
            # Not Thread.join: an exception raised inside it marks the thread ended.
            while not finished.wait(RAY_POLL_S):
                pass
            break
        except KeyboardInterrupt:
            cancel.set()
            if case_thread.ident is None:
                raise
    (result,) = outcome
    if isinstance(result, BaseException):
        raise result
    return result


def _ray_result(ray: Any, ref: Any, case: CaseSpec) -> Result | None:
    """A task's result; None for a task cancelled before its case began."""
    try:
        result: Result = ray.get(ref)
    except ray.exceptions.TaskCancelledError:
        return None
    except ray.exceptions.RayError as error:
        reason = f"Ray task failed: {error}"
        return {"name": case.name, "parameters": case.parameters, "status": ERROR, "reason": reason}
    return result


def failed(result: Result) -> bool:
    return result["status"] != PASSED
