"""ragdoll_batch: many falls from one scenario file into a CSV, and plots of the results.

    ragdoll_batch run SCENARIO.yaml --runs 0:1000 --out results.csv [--scheduler tcp://H:P]
                                    [--workers N] [--chunk-size K]
    ragdoll_batch report results.csv [--out DIR]

Exit status 1 with one message naming the problem for a bad scenario, results file or option.
See docs/batch.md.
"""
import argparse
import sys

from . import csv_rows, fanout, runner, scenario as scenario_mod


class UsageError(ValueError):
    """A bad command-line value; str() names the option."""


class RunError(RuntimeError):
    """The runs could not finish (the Dask cluster failed); str() says why."""


def parse_runs(text):
    """'A:B' -> range(A, B); 'N' -> range(0, N)."""
    try:
        if ":" in text:
            a, b = text.split(":", 1)
            lo, hi = int(a), int(b)
        else:
            lo, hi = 0, int(text)
    except ValueError:
        raise UsageError("--runs: expected START:END or COUNT (integers), got \"%s\"" % text)
    if lo < 0 or hi < lo:
        raise UsageError("--runs: expected 0 <= START <= END, got \"%s\"" % text)
    return range(lo, hi)


def _progress(total):
    """A tqdm bar on a terminal (stderr), else None."""
    if not sys.stderr.isatty():
        return None
    try:
        from tqdm import tqdm
    except ImportError:
        return None
    return tqdm(total=total, unit="run", file=sys.stderr)


def load_checked(path):
    """The validated scenario with its model and world loaded; ScenarioError naming the field."""
    sc = scenario_mod.load(path)
    for field, load in (("model", runner.model), ("world", runner.world)):
        try:
            load(sc[field])
        except (RuntimeError, ValueError) as e:
            raise scenario_mod.ScenarioError("scenario: %s: %s" % (field, e))
    problems = runner.check(sc)
    if problems:
        raise scenario_mod.ScenarioError("scenario: " + problems[0])
    return sc


def run(args):
    """`ragdoll_batch run`: the runs of --runs not yet in --out, appended to it."""
    indices = parse_runs(args.runs)
    if args.workers is not None and args.workers < 1:
        raise UsageError("--workers: expected a number >= 1, got %d" % args.workers)
    if args.scheduler is not None and args.workers is not None:
        raise UsageError("--scheduler and --workers: give one (a scheduler's cluster has its own "
                         "workers)")
    if args.chunk_size is not None and args.chunk_size < 1:
        raise UsageError("--chunk-size: expected a number >= 1, got %d" % args.chunk_size)
    sc = load_checked(args.scenario)
    cols = runner.columns(sc)
    done = csv_rows.done_indices(args.out, cols)
    todo = [i for i in indices if i not in done]
    writer = csv_rows.Writer(args.out, cols)
    bar = _progress(len(todo))
    try:
        if args.scheduler is None and args.workers == 1:
            for i in todo:
                writer.write(runner.run_chunk(sc, [i]))
                if bar is not None:
                    bar.update(1)
        elif todo:
            try:
                fanout.run(sc, todo, writer.write, scheduler=args.scheduler,
                           workers=args.workers, chunk_size=args.chunk_size,
                           progress=(lambda n: bar.update(n)) if bar is not None else None)
            except fanout.FanoutError as e:
                raise RunError("ragdoll_batch: %s (the rows written so far are kept: run again "
                               "to resume)" % e)
    finally:
        writer.close()
        if bar is not None:
            bar.close()
    print("%s: %d runs written, %d already there" % (args.out, len(todo), len(indices) - len(todo)),
          file=sys.stderr)
    return 0


def report(args):
    """`ragdoll_batch report`: PNG plots and summary.md of a results CSV."""
    from . import report as report_mod
    out = report_mod.write_report(args.results, args.out)
    for path in out:
        print(path)
    return 0


def parser():
    """The argument parser of ragdoll_batch."""
    p = argparse.ArgumentParser(prog="ragdoll_batch", description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="run the falls of a scenario into a CSV (resumable)")
    r.add_argument("scenario", help="scenario YAML file (docs/batch.md)")
    r.add_argument("--runs", default="0:100",
                   help="START:END (END excluded) or COUNT; default 0:100")
    r.add_argument("--out", required=True, help="results CSV; runs already in it are skipped")
    r.add_argument("--scheduler", help="Dask scheduler address tcp://HOST:PORT")
    r.add_argument("--workers", type=int, help="1: in this process; N: a local Dask cluster of N "
                   "processes (default: every core)")
    r.add_argument("--chunk-size", type=int, help="runs per Dask task (default: the fan-out's)")
    r.set_defaults(func=run)
    s = sub.add_parser("report", help="plots (PNG) and a Markdown summary of a results CSV")
    s.add_argument("results", help="results CSV of `ragdoll_batch run`")
    s.add_argument("--out", help="folder for the report (default: RESULTS_report next to it)")
    s.set_defaults(func=report)
    return p


def main(argv=None):
    """Entry point of scripts/ragdoll_batch; returns the exit status."""
    args = parser().parse_args(argv)
    try:
        return args.func(args)
    except (scenario_mod.ScenarioError, csv_rows.ResultsError, UsageError, RunError) as e:
        print(str(e), file=sys.stderr)
        return 1
    except OSError as e:
        print("ragdoll_batch: %s" % e, file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("ragdoll_batch: interrupted; the rows written so far are kept (run again to "
              "resume)", file=sys.stderr)
        return 130
