"""fanout.run on a LocalCluster of 2 workers gives the in-process rows, each index once."""

import collections

import pytest

import fanout_support as fs
from ragdoll_sim.batch import fanout

N = 24


@pytest.fixture(scope="module")
def scen():
    return fs.scenario()


@pytest.fixture(scope="module")
def reference(scen):
    return fs.canonical(fs.run_chunk(scen, list(range(N))))


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    """One LocalCluster of 2 single-thread workers shared by the tests that pass its address."""
    from distributed import LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=None,
                      local_directory=str(tmp_path_factory.mktemp("dask"))) as c:
        yield c


class Collector:
    """on_rows and progress callbacks that record every call."""

    def __init__(self):
        self.calls = []
        self.progress = []

    def on_rows(self, rows):
        self.calls.append(list(rows))

    def on_progress(self, n):
        self.progress.append(n)

    @property
    def rows(self):
        return [r for call in self.calls for r in call]


def check_once(col, indices, reference):
    counts = collections.Counter(r["index"] for r in col.rows)
    duplicates = sorted(i for i, c in counts.items() if c > 1)
    missing = sorted(set(indices) - set(counts))
    assert not duplicates, f"indices delivered twice: {duplicates}"
    assert not missing, f"indices never delivered: {missing}"
    assert fs.canonical(col.rows) == reference
    assert sum(col.progress) == len(indices)
    assert len(col.progress) == len(col.calls)


def test_local_cluster_of_two_workers(scen, reference):
    """The default path: fanout starts (and stops) its own LocalCluster of 2 processes."""
    col = Collector()
    n = fanout.run(scen, range(N), col.on_rows, workers=2, chunk_size=5,
                   progress=col.on_progress, task=fs.run_chunk)
    assert n == N
    check_once(col, range(N), reference)
    assert [len(c) for c in col.calls] and max(len(c) for c in col.calls) <= 5


@pytest.mark.parametrize("chunk_size", [1, 3, 7, None, 1000])
def test_any_chunk_size(scen, reference, cluster, chunk_size):
    col = Collector()
    fanout.run(scen, range(N), col.on_rows, scheduler=cluster.scheduler_address,
               chunk_size=chunk_size, progress=col.on_progress, task=fs.run_chunk)
    check_once(col, range(N), reference)
    if chunk_size:
        assert len(col.calls) == -(-N // chunk_size)


def test_unordered_subset(scen, reference, cluster):
    """The indices left to do after a resumed run: any subset, in any order."""
    indices = [17, 3, 22, 8, 9, 0]
    col = Collector()
    fanout.run(scen, indices, col.on_rows, scheduler=cluster.scheduler_address, chunk_size=4,
               progress=col.on_progress, task=fs.run_chunk)
    want = [reference[i] for i in sorted(indices)]
    check_once(col, indices, want)


def test_failing_run_is_named(scen, cluster):
    with pytest.raises(fanout.FanoutError, match=r"run 13 .*ValueError: push out of range"):
        fanout.run(scen, range(N), lambda rows: None, scheduler=cluster.scheduler_address,
                   chunk_size=4, task=fs.failing_run_chunk)


def test_unreachable_scheduler_is_named(scen, monkeypatch):
    monkeypatch.setattr(fanout, "CONNECT_TIMEOUT_S", 1)
    address = f"tcp://127.0.0.1:{fs.free_port()}"
    with pytest.raises(fanout.FanoutError, match="cannot reach the Dask scheduler at " + address):
        fanout.run(scen, range(3), lambda rows: None, scheduler=address, task=fs.run_chunk)


@pytest.mark.parametrize("kwargs, message", [
    ({"indices": [1, 2, 1]}, "run index 1 is given twice"),
    ({"workers": 0}, "workers must be a positive integer, got 0"),
    ({"chunk_size": -3}, "chunk_size must be a positive integer, got -3"),
    ({"scheduler": "localhost"}, "scheduler must be an address like tcp://HOST:8786"),
    ({"scheduler": "tcp://h:1", "workers": 2}, "give scheduler"),
])
def test_bad_arguments_are_named(scen, kwargs, message):
    args = {"indices": [0, 1], **kwargs}
    indices = args.pop("indices")
    with pytest.raises(ValueError, match=message):
        fanout.run(scen, indices, lambda rows: None, task=fs.run_chunk, **args)


def test_nothing_to_do_starts_nothing(scen):
    assert fanout.run(scen, [], lambda rows: pytest.fail("no rows expected")) == 0
