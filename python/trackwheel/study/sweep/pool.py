"""Running a sweep's cases in parallel: a process pool of our own (forkserver, never fork) or
any ``concurrent.futures.Executor``; every case that finishes is kept, whatever happens to
the others."""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import signal
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool

from . import cases


def default_workers() -> int:
    """The cores this process may run on (os.cpu_count() where affinity is unknown)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


def make_pool(workers: int) -> ProcessPoolExecutor:
    """A process pool of ``workers`` processes."""
    # forkserver (POSIX) or spawn: never fork a parent that may run threads (progress bars,
    # Jupyter, Dask); the workers import trackwheel afresh and run cases.run_case by name.
    if "forkserver" in multiprocessing.get_all_start_methods():
        ctx = multiprocessing.get_context("forkserver")
        # The server (started once per session) imports trackwheel once; the workers of every
        # sweep fork from it ready to run: ~0.1 s instead of ~0.5-1 s per pool. "__main__" is
        # the default preload; scipy.interpolate is what a case imports on first use (the rail
        # profile's spline), which each worker would otherwise pay at its first rough case
        # (half a second or more). No effect if the server already runs.
        ctx.set_forkserver_preload(["__main__", cases.__name__, "scipy.interpolate"])
    else:
        ctx = multiprocessing.get_context("spawn")
    return ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=_ignore_ctrl_c)


def _ignore_ctrl_c() -> None:
    """In a worker: ignore SIGINT. Ctrl-C at a terminal reaches the whole process group; the
    parent handles it (keeps the finished cases, terminates the workers), so the workers must
    not die each with a KeyboardInterrupt traceback."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def terminate(pool: ProcessPoolExecutor) -> None:
    """Stop our own pool's worker processes now (after Ctrl-C: their cases are abandoned)."""
    stop = getattr(pool, "terminate_workers", None)  # Python >= 3.14
    if stop is not None:
        stop()
        return
    procs = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for proc in procs:  # our own workers, by handle
        with contextlib.suppress(OSError):
            proc.terminate()
    for proc in procs:
        proc.join(timeout=5.0)


def run_parallel(ex, own: bool, todo, case_list, kwargs, finish) -> None:
    """Run the cases ``todo`` (indices into ``case_list``: (speed, stiffness, seed, scene,
    ...)) on the executor ``ex`` (``own``: our pool, which may be terminated), calling
    ``finish(i, row)`` in this process as each comes back. Ctrl-C, or a case raising something
    unexpected, keeps every case that still finishes and re-raises."""
    pending = {ex.submit(cases.run_case, case_list[i][3], case_list[i][0], kwargs): i
               for i in todo}
    try:
        while pending:
            done, _ = wait(pending, return_when=FIRST_COMPLETED)
            for fut in done:
                i = pending.pop(fut)
                finish(i, fut.result())
    except KeyboardInterrupt:
        for fut in pending:
            fut.cancel()
        for fut in [f for f in pending if f.done() and not f.cancelled()]:
            if fut.exception() is None:  # finished meanwhile: keep it
                finish(pending[fut], fut.result())
        if own:
            terminate(ex)
        raise
    except BaseException as exc:
        # a case raised something unexpected: keep every case that still finishes, then raise
        if own and isinstance(exc, BrokenProcessPool) and hasattr(exc, "add_note"):
            exc.add_note("trackwheel.sweep: a worker process died. Run from a script, the "
                         "sweep must sit under `if __name__ == \"__main__\":` (the workers "
                         "import the main module); max_workers=1 runs without workers.")
        for fut in pending:
            fut.cancel()
        running = [f for f in pending if not f.cancelled()]
        wait(running)
        for fut in running:
            if fut.exception() is None:
                finish(pending[fut], fut.result())
        raise
