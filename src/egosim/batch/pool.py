"""Running many cases: a local pool of N worker slots, or one Ray actor per slot.

A slot runs one case at a time and keeps a warm simulator worker (warm_simulator) from
one case to the next (in the local pool, one the batch command started as it began:
early_workers); a case's stack is its own process. In the local pool a slot's
cases overlap at their ends: the next one's stack starts while the last one drives, and
the last one's stack ends while the next one runs (local_slot). The local pool only supervises:
N threads, each waiting on its slot's case. When the batch is interrupted, every running
case's processes are stopped (their scores so far are kept) and the cases not started are
reported not run, in the local pool and on Ray alike.
"""

from __future__ import annotations

import importlib
import queue
import threading
from collections import deque
from collections.abc import Callable, Sequence
from typing import Protocol, cast

from egosim.batch.case import CaseSpec
from egosim.batch.case_runner import ERROR, PASSED, EndingCase, run_case
from egosim.batch.documents import CaseResult
from egosim.batch.early_workers import EarlyWorkers
from egosim.batch.interrupt import Interrupt
from egosim.batch.local_slot import DriveTimes, LocalSlot
from egosim.batch.warm_simulator import WarmSimulator

Result = CaseResult
OnResult = Callable[[Result, int], None]
"""Called with each finished case's result and the number of cases still running."""

ObjectRef = object
"""A Ray future: only waited for, got and used as a key here."""

POLL_S = 0.2
RAY_CLOSE_S = 60.0
"""Time for every actor to end its simulator worker when a Ray batch ends."""


def run_local(
    cases: Sequence[CaseSpec],
    out_dir: str,
    workers: int,
    on_result: OnResult,
    results: dict[str, Result] | None = None,
    interrupt: Interrupt | None = None,
    early: EarlyWorkers | None = None,
) -> dict[str, Result]:
    """Run `cases`, `workers` at a time; their results by name, also put in `results` as
    they come. Once `interrupt` stops the batch, the running cases end (their results
    kept) and no other starts. The slots take their simulator workers from `early` (the
    workers it has left end at once), else start their own."""
    interrupt = interrupt or Interrupt()
    early = early or EarlyWorkers(0)
    results = {} if results is None else results
    todo: deque[CaseSpec] = deque(cases)
    finished: queue.Queue[Result] = queue.Queue()
    running = [0]
    lock = threading.Lock()

    def next_case() -> CaseSpec | None:
        with lock:
            if interrupt.stop.is_set() or not todo:
                return None
            running[0] += 1
            return todo.popleft()

    def give_back() -> None:
        with lock:
            running[0] -= 1

    def deliver(case: EndingCase) -> None:
        result = case.finish()
        give_back()
        finished.put(result)

    times = DriveTimes()
    slots = [
        LocalSlot(
            out_dir, early.take(), next_case, give_back, deliver, times, interrupt, f"case slot {k}"
        )
        for k in range(min(workers, len(cases)))
    ]
    early.close()
    threads = [threading.Thread(target=slot.run, name=slot.name) for slot in slots]
    for thread in threads:
        thread.start()
    while any(thread.is_alive() for thread in threads) or not finished.empty():
        try:
            result = finished.get(timeout=POLL_S)
        except queue.Empty:
            continue
        results[result["name"]] = result
        on_result(result, running[0])
    for thread in threads:
        thread.join()
    return results


def run_ray(
    cases: Sequence[CaseSpec],
    out_dir: str,
    address: str | None,
    on_result: OnResult,
    results: dict[str, Result] | None = None,
    interrupt: Interrupt | None = None,
    on_connected: Callable[[], None] | None = None,
) -> dict[str, Result]:
    """The cases on the Ray cluster at `address` (None: the one `ray start` left running
    on this machine, else a new local one), one actor per CPU of the cluster (one case at
    a time each, its simulator worker kept warm); results and `interrupt` as run_local's.
    `on_connected` runs once Ray is up (ray.init installs signal handlers of its own). The
    output folder must be on storage every node writes to."""
    # An optional extra (pip install egosim[ray]), so typed by the part used here.
    ray = cast(_Ray, importlib.import_module("ray"))
    interrupt = interrupt or Interrupt()
    results = {} if results is None else results
    ray.init(address=address, include_dashboard=False, log_to_driver=False)
    if on_connected is not None:
        on_connected()
    actors: list[_CaseSlotActor] = []
    try:
        slots = min(len(cases), max(int(ray.cluster_resources().get("CPU", 1)), 1))
        # Three at once: a case, and the driver's calls to stop or hurry it.
        remote = ray.remote(num_cpus=1, max_concurrency=3, max_restarts=-1)(CaseSlot)
        actors = [remote.remote() for _ in range(slots)]
        _dispatch(ray, actors, cases, out_dir, on_result, results, interrupt)
        return results
    finally:
        if actors:
            closing = [actor.close.remote(interrupt.hurry.is_set()) for actor in actors]
            ray.wait(closing, num_returns=len(closing), timeout=RAY_CLOSE_S)
            for actor in actors:
                ray.kill(actor)
        ray.shutdown()


def _dispatch(
    ray: _Ray,
    actors: list[_CaseSlotActor],
    cases: Sequence[CaseSpec],
    out_dir: str,
    on_result: OnResult,
    results: dict[str, Result],
    interrupt: Interrupt,
) -> None:
    """Hand each idle actor the next case until every case has run or the batch stops."""
    todo = deque(cases)
    idle = list(actors)
    running: dict[ObjectRef, tuple[_CaseSlotActor, CaseSpec]] = {}
    told: set[threading.Event] = set()
    calls: tuple[tuple[threading.Event, Callable[[_CaseSlotActor], _RemoteMethod]], ...] = (
        (interrupt.stop, lambda actor: actor.stop),
        (interrupt.hurry, lambda actor: actor.hurry),
    )
    while running or (todo and not interrupt.stop.is_set()):
        while idle and todo and not interrupt.stop.is_set():
            actor, case = idle.pop(), todo.popleft()
            running[actor.run.remote(case, out_dir)] = (actor, case)
        for event, method in calls:
            if event.is_set() and event not in told:
                told.add(event)
                for actor, _ in running.values():
                    method(actor).remote()
        done, _ = ray.wait(list(running), num_returns=1, timeout=POLL_S)
        for ref in done:
            actor, case = running.pop(ref)
            idle.append(actor)
            result = _ray_result(ray, ref, case)
            if result is not None:
                results[result["name"]] = result
                on_result(result, len(running))


class CaseSlot:
    """A Ray actor: one case at a time on a warm simulator worker of its own, as a slot of
    the local pool runs them. `stop` and `hurry` come from the driver while a case runs
    (Ray does not interrupt a running actor call)."""

    def __init__(self) -> None:
        self.simulator = WarmSimulator()
        self.interrupt = Interrupt()

    def run(self, case: CaseSpec, out_dir: str) -> Result | None:
        """The case's result; None when the batch was stopped before it began."""
        if self.interrupt.stop.is_set():
            return None
        return run_case(case, out_dir, self.simulator, self.interrupt)

    def stop(self) -> None:
        self.interrupt.stop.set()

    def hurry(self) -> None:
        self.interrupt.stop.set()
        self.interrupt.hurry.set()

    def close(self, hurry: bool) -> None:
        if hurry:
            self.hurry()
        self.simulator.close(self.interrupt.hurry)


def _ray_result(ray: _Ray, ref: ObjectRef, case: CaseSpec) -> Result | None:
    """An actor call's result; None for a case the batch stopped before it began."""
    try:
        result = ray.get(ref)
    except ray.exceptions.RayError as error:
        reason = f"Ray task failed: {error}"
        return {"name": case.name, "parameters": case.parameters, "status": ERROR, "reason": reason}
    return result


def failed(result: Result) -> bool:
    return bool(result["status"] != PASSED)


class _RemoteMethod(Protocol):
    def remote(self, *args: object) -> ObjectRef: ...


class _CaseSlotActor(Protocol):
    """A CaseSlot on Ray: each method called with .remote(...)."""

    @property
    def run(self) -> _RemoteMethod: ...
    @property
    def stop(self) -> _RemoteMethod: ...
    @property
    def hurry(self) -> _RemoteMethod: ...
    @property
    def close(self) -> _RemoteMethod: ...


class _ActorClass(Protocol):
    def remote(self) -> _CaseSlotActor: ...


class _RayExceptions(Protocol):
    @property
    def RayError(self) -> type[Exception]: ...  # noqa: N802 (Ray's name)


class _Ray(Protocol):
    """What of the `ray` module the pool uses."""

    @property
    def exceptions(self) -> _RayExceptions: ...
    def init(
        self, *, address: str | None, include_dashboard: bool, log_to_driver: bool
    ) -> object: ...
    def cluster_resources(self) -> dict[str, float]: ...
    def remote(
        self, *, num_cpus: int, max_concurrency: int, max_restarts: int
    ) -> Callable[[type[CaseSlot]], _ActorClass]: ...
    def wait(
        self, refs: list[ObjectRef], *, num_returns: int, timeout: float | None
    ) -> tuple[list[ObjectRef], list[ObjectRef]]: ...
    def get(self, ref: ObjectRef) -> Result | None:
        """(Every ref got here is a CaseSlot.run call's.)"""

    def kill(self, actor: _CaseSlotActor) -> None: ...
    def shutdown(self) -> None: ...
