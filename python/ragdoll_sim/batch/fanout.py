"""Fan-out of batch runs over Dask distributed.

Chunks of run indices become Dask tasks that call ``runner.run_chunk`` on the workers; the
rows come back to the caller's process, one ``on_rows(rows)`` call per finished chunk. A
worker that dies takes only its unfinished chunks with it: the scheduler reruns them on
another worker, and every index is still handed to ``on_rows`` exactly once.

The workers unpickle the task by reference, so they must import the same ``ragdoll_sim``
as the caller: start each ``dask-worker`` from a shell that sourced the same workspace's
``devel/setup.bash`` (a LocalCluster's worker processes inherit the caller's environment).
See docs/distributed.md.
"""

import logging
import math
import shutil
import tempfile

__all__ = ["run", "chunks", "default_chunk_size", "run_indices", "FanoutError", "RunFailed"]

#: Seconds to wait for a TCP connection to the scheduler before giving up.
CONNECT_TIMEOUT_S = 10
#: Seconds to wait for the first worker to join an external scheduler.
WORKER_WAIT_S = 60
#: A chunk that was on ALLOWED_FAILURES + 1 dying workers is reported as a crash, not rerun;
#: one lost worker is an accident, several in a row point at the simulation itself.
ALLOWED_FAILURES = 3
#: Chunks per worker thread by default: enough to balance uneven falls and to lose little
#: when a worker dies, few enough that the scheduler's per-task cost stays negligible.
CHUNKS_PER_THREAD = 8
#: Largest default chunk, in runs.
MAX_DEFAULT_CHUNK = 64


class FanoutError(RuntimeError):
    """A fan-out could not finish: the scheduler, a worker or a run failed (message says which)."""


class RunFailed(RuntimeError):
    """Raised on a worker when the task fails for one index: args are (index, message)."""

    def __init__(self, index, message):
        super().__init__(index, message)

    @property
    def index(self):
        """The run index that failed."""
        return self.args[0]

    @property
    def message(self):
        """The failure, as 'ExceptionType: text'."""
        return self.args[1]

    def __str__(self):
        return f"run {self.args[0]}: {self.args[1]}"


def chunks(indices, size):
    """Split ``indices`` into consecutive lists of at most ``size`` indices, in order."""
    indices = list(indices)
    return [indices[k:k + size] for k in range(0, len(indices), size)]


def default_chunk_size(n_indices, n_threads):
    """The chunk size used when none is given: about CHUNKS_PER_THREAD chunks per worker thread."""
    per = math.ceil(n_indices / max(1, n_threads * CHUNKS_PER_THREAD))
    return max(1, min(MAX_DEFAULT_CHUNK, per))


def _describe(exc):
    return f"{type(exc).__name__}: {exc}"


def run_indices(task, scenario, indices):
    """The Dask task: ``task(scenario, indices)``, checked to give one row per index, in order.

    When the chunk fails, each index is run alone to name the one that fails; raises RunFailed.
    """
    try:
        rows = list(task(scenario, list(indices)))
    except Exception as exc:  # noqa: BLE001 -- any failure is reported with its index
        chunk_error = exc
    else:
        _check_rows(rows, indices)
        return rows
    for i in indices:
        try:
            task(scenario, [i])
        except Exception as exc:  # noqa: BLE001
            raise RunFailed(i, _describe(exc)) from None
    raise RunFailed(indices[0], f"runs {indices[0]}..{indices[-1]} fail together but not alone: "
                                f"{_describe(chunk_error)}")


def _check_rows(rows, indices):
    if len(rows) != len(indices):
        raise RunFailed(indices[0], f"the task returned {len(rows)} rows for {len(indices)} runs "
                                    f"({indices[0]}..{indices[-1]})")
    for i, row in zip(indices, rows):
        if isinstance(row, dict) and "index" in row and row["index"] != i:
            raise RunFailed(i, f"the task returned the row of run {row['index']} in its place")


def _chunk_key(task, scenario, chunk):
    # The key is a hash of what the chunk computes, so a rerun recomputes the same key and a
    # second submission of the same chunk shares it instead of computing a duplicate.
    from dask.base import tokenize
    name = getattr(task, "__name__", "task")
    return f"ragdoll-{name}-{chunk[0]}-{chunk[-1]}-{tokenize(task, scenario, chunk)}"


def _validate(indices, on_rows, scheduler, workers, chunk_size, progress):
    if not callable(on_rows):
        raise TypeError(f"on_rows must be callable, got {type(on_rows).__name__}")
    if progress is not None and not callable(progress):
        raise TypeError(f"progress must be callable or None, got {type(progress).__name__}")
    if scheduler is not None and workers is not None:
        raise ValueError(f"give scheduler ({scheduler!r}) or workers ({workers!r}), not both: "
                         "an external cluster has its own workers")
    if scheduler is not None and (not isinstance(scheduler, str) or "://" not in scheduler):
        raise ValueError(f"scheduler must be an address like tcp://HOST:8786, got {scheduler!r}")
    for name, value in (("workers", workers), ("chunk_size", chunk_size)):
        if value is not None and (isinstance(value, bool) or not isinstance(value, int)
                                  or value < 1):
            raise ValueError(f"{name} must be a positive integer, got {value!r}")
    seen = set()
    for i in indices:
        if isinstance(i, bool) or not isinstance(i, int):
            raise ValueError(f"run indices must be integers, got {i!r}")
        if i in seen:
            raise ValueError(f"run index {i} is given twice")
        seen.add(i)


def run(scenario, indices, on_rows, scheduler=None, workers=None, chunk_size=None,
        progress=None, task=None):
    """Run ``task(scenario, chunk)`` for chunks of ``indices`` on Dask; hand back rows as they come.

    scenario: the validated scenario dict (picklable), sent with every chunk.
    indices: the run indices (distinct integers).
    on_rows(rows): called in the caller's process once per finished chunk, with that chunk's
        rows in index order; over the whole run every index arrives exactly once, also when
        workers die (their chunks are rerun elsewhere).
    scheduler: "tcp://HOST:PORT" of a running dask-scheduler; None starts a LocalCluster.
    workers: the LocalCluster's worker processes (one thread each), default every core this
        process may run on.
    chunk_size: runs per task; default about CHUNKS_PER_THREAD chunks per worker thread.
    progress(n): called after each on_rows with the number of runs just delivered.
    task: the function run on the workers, default ragdoll_sim.batch.runner.run_chunk.
    Returns the number of runs delivered. Raises FanoutError naming the scheduler address when
    it cannot be reached, the run index and message when a run fails, the runs when a chunk
    keeps killing workers. On any error or KeyboardInterrupt the chunks not yet finished are
    cancelled and a LocalCluster is shut down with its worker processes.
    """
    indices = list(indices)
    _validate(indices, on_rows, scheduler, workers, chunk_size, progress)
    if not indices:
        return 0
    if task is None:
        from ragdoll_sim.batch.runner import run_chunk as task
    import dask
    import distributed  # noqa: F401 -- loads its config defaults, which config.set must not hide
    with dask.config.set({"distributed.scheduler.allowed-failures": ALLOWED_FAILURES}):
        if scheduler is not None:
            with _connect(scheduler) as client:
                return _fan_out(client, task, scenario, indices, on_rows, chunk_size, progress,
                                scheduler)
        with _local_cluster(workers) as client:
            return _fan_out(client, task, scenario, indices, on_rows, chunk_size, progress,
                            "a local cluster")


class _connect:
    """Context manager: a Client of the scheduler at ``address`` with at least one worker."""

    def __init__(self, address):
        self.address = address
        self.client = None

    def __enter__(self):
        from distributed import Client
        try:
            self.client = Client(self.address, timeout=CONNECT_TIMEOUT_S, set_as_default=False)
        except (OSError, TimeoutError) as exc:
            raise FanoutError(f"cannot reach the Dask scheduler at {self.address}: "
                              f"{_describe(exc)}; is dask-scheduler running there, and is its "
                              "port open?") from None
        try:
            self.client.wait_for_workers(1, timeout=WORKER_WAIT_S)
        except (OSError, TimeoutError):
            self.client.close()
            raise FanoutError(f"no worker joined the Dask scheduler at {self.address} within "
                              f"{WORKER_WAIT_S} s: start `dask-worker {self.address}` on each "
                              "host") from None
        return self.client

    def __exit__(self, *exc):
        self.client.close()
        return False


class _local_cluster:
    """Context manager: a Client of a fresh LocalCluster whose files go to a temporary folder."""

    def __init__(self, workers):
        self.workers = workers
        self.cluster = self.client = None
        self.tmp = None

    def __enter__(self):
        import os
        from distributed import Client, LocalCluster
        self.tmp = tempfile.mkdtemp(prefix="ragdoll-dask-")
        n = self.workers or len(os.sched_getaffinity(0)) or 1
        try:
            self.cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                        host="127.0.0.1", dashboard_address=None,
                                        local_directory=self.tmp, silence_logs=logging.ERROR)
            self.client = Client(self.cluster, set_as_default=False)
        except BaseException:
            self.__exit__()
            raise
        return self.client

    def __exit__(self, *exc):
        try:
            if self.client is not None:
                self.client.close()
            if self.cluster is not None:
                self.cluster.close()
        finally:
            shutil.rmtree(self.tmp, ignore_errors=True)
        return False


def _fan_out(client, task, scenario, indices, on_rows, chunk_size, progress, where):
    from distributed import as_completed
    if chunk_size is None:
        chunk_size = default_chunk_size(len(indices), sum(client.nthreads().values()))
    parts = chunks(indices, chunk_size)
    futures = {}
    try:
        for part in parts:
            future = client.submit(run_indices, task, scenario, part,
                                   key=_chunk_key(task, scenario, part), retries=0)
            futures[future.key] = (future, part)
        delivered = 0
        for future in as_completed([f for f, _ in futures.values()], loop=client.loop):
            part = futures[future.key][1]
            rows = _result(future, part, where)
            on_rows(rows)
            delivered += len(part)
            future.release()
            if progress is not None:
                progress(len(part))
        return delivered
    finally:
        pending = [f for f, _ in futures.values() if not f.done()]
        if pending:
            try:
                client.cancel(pending)
            except Exception:  # noqa: BLE001 -- the client may be gone already; closing follows
                pass


def _result(future, part, where):
    from distributed import KilledWorker
    try:
        return future.result()
    except RunFailed as exc:
        raise FanoutError(f"run {exc.index} failed on a worker of {where}: {exc.message}") \
            from None
    except KilledWorker as exc:
        n = exc.allowed_failures + 1
        raise FanoutError(f"runs {part[0]}..{part[-1]} were lost with {n} dying worker"
                          f"{'s' if n > 1 else ''} of {where} (allowed-failures "
                          f"{exc.allowed_failures}): a crash of the simulation is likely; run "
                          "them in one process (ragdoll_batch run --workers 1) to see it") from None
    except (ImportError, AttributeError) as exc:
        raise FanoutError(f"runs {part[0]}..{part[-1]}: a worker of {where} cannot load the task "
                          f"({_describe(exc)}); start every worker after sourcing the same "
                          "workspace's devel/setup.bash") from None
    except Exception as exc:  # noqa: BLE001 -- anything else from the worker, named
        raise FanoutError(f"runs {part[0]}..{part[-1]} failed on a worker of {where}: "
                          f"{_describe(exc)}") from None
