"""ragdoll_batch: rows as pure functions of (scenario, index), the CSV's columns and exact floats,
resume, refusals of bad scenarios naming the field (exit 1), and the report's files and counts.
Short falls (0.4 s) down the shipped stairs, few runs.
"""
import csv
import math
import os
import subprocess
import sys

import pytest

from ragdoll_sim.batch import cli, csv_rows, report, runner, sampling, scenario

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
SCRIPT = os.path.join(ROOT, "scripts", "ragdoll_batch")

SHORT = """\
seed: 5
duration: 0.4
world: stairs
spawn:
  x: {uniform: [-0.4, -0.1]}
  z: 2.56
  yaw: {normal: {mean: 0.0, std: 0.2}}
  vx: {uniform: [0.5, 1.5]}
  wy: 1.5
push:
  link: {choice: [torso, head]}
  direction: [1.0, {uniform: [-0.3, 0.3]}, 0.0]
  size: {uniform: [10.0, 60.0]}
material:
  friction: {uniform: [0.5, 1.0]}
  restitution: 0.1
"""


@pytest.fixture(scope="module")
def short_path(tmp_path_factory):
    path = tmp_path_factory.mktemp("scenario") / "short.yaml"
    path.write_text(SHORT)
    return str(path)


@pytest.fixture(scope="module")
def short(short_path):
    return scenario.load(short_path)


def batch(*args):
    """ragdoll_batch as a user runs it: (exit status, stdout, stderr)."""
    p = subprocess.run([sys.executable, SCRIPT] + list(args), capture_output=True, text=True,
                       timeout=60)
    return p.returncode, p.stdout, p.stderr


def test_draws_are_splitmix64_and_deterministic_log():
    # splitmix64's first output from state 0 (the reference implementation's).
    assert sampling.splitmix64(0) == 0xE220A8397B1DCDAF
    for x in (1e-300, 1e-5, 0.1, 0.5, 0.7071, 0.9999, 1.0, 3.0, 1e300):
        assert math.isclose(sampling.det_log(x), math.log(x), rel_tol=4e-16, abs_tol=1e-300)
    n = [sampling.Draws(1, i).normal("a", 2.0, 3.0) for i in range(4000)]
    mean = sum(n) / len(n)
    std = math.sqrt(sum((v - mean) ** 2 for v in n) / len(n))
    assert abs(mean - 2.0) < 0.15 and abs(std - 3.0) < 0.15
    u = [sampling.Draws(1, i).uniform("b", -1.0, 1.0) for i in range(4000)]
    assert -1.0 <= min(u) and max(u) < 1.0 and abs(sum(u) / len(u)) < 0.05
    # streams by name: another parameter, another draw
    assert sampling.Draws(1, 0).uniform("a", 0, 1) != sampling.Draws(1, 0).uniform("b", 0, 1)


def test_columns_are_the_issues(short):
    cols = runner.columns(short)
    links = runner.model(short["model"]).link_names
    assert "head" in links and "torso" in links
    expected = (["index"]
                + ["spawn_" + f for f in ("x", "y", "z", "roll", "pitch", "yaw",
                                          "vx", "vy", "vz", "wx", "wy", "wz")]
                + ["push_link", "push_size", "push_dx", "push_dy", "push_dz",
                   "friction", "restitution", "contact_hertz"]
                + ["rest_class", "rest_x", "rest_y", "rest_z", "rest_roll", "rest_pitch",
                   "rest_yaw", "head_peak_g", "hic15"]
                + ["force_" + l for l in links]
                + ["broken_joints", "time_to_rest", "nan"])
    assert cols == expected


def test_same_index_same_row_in_any_order_and_process(short, short_path):
    forward = runner.run_chunk(short, [0, 1, 2])
    backward = runner.run_chunk(short, [2, 1, 0])[::-1]
    assert [r["index"] for r in forward] == [0, 1, 2]
    assert [list(r) for r in forward] == [runner.columns(short)] * 3
    assert [repr(r) for r in forward] == [repr(r) for r in backward]
    # the runs differ from each other and fell: the push and the landing left their marks
    assert len({r["push_size"] for r in forward}) == 3
    assert all(r["head_peak_g"] > 0 for r in forward)
    assert any(max(r[c] for c in r if c.startswith("force_")) > 0 for r in forward)
    code = ("import sys; from ragdoll_sim.batch import runner, scenario; "
            "sc = scenario.load(sys.argv[1]); print(repr(runner.run_chunk(sc, [1])[0]))")
    fresh = subprocess.run([sys.executable, "-c", code, short_path], capture_output=True,
                           text=True, timeout=60)
    assert fresh.returncode == 0, fresh.stderr
    assert fresh.stdout.strip() == repr(forward[1])


def test_lanes_widths_give_the_same_rows(short):
    rows = runner.run_chunk(dict(short, lanes=4), [0, 1])
    eight = runner.run_chunk(dict(short, lanes=8), [0, 1])
    assert [repr(r) for r in rows] == [repr(r) for r in eight]
    assert all(r["head_peak_g"] > 0 for r in rows)
    # the lanes reach the runs: double rows round otherwise
    double = runner.run_chunk(dict(short, lanes=1), [0, 1])
    assert [repr(r) for r in rows] != [repr(r) for r in double]
    # lanes 0, and a scenario without lanes (the solver's default, 0), run the lanes from 24
    # awake bodies: the lone ragdoll on the stairs takes the double rows
    assert short["lanes"] is None
    for automatic in (short, dict(short, lanes=0)):
        assert [repr(r) for r in runner.run_chunk(automatic, [0, 1])] == [repr(r) for r in double]
    # a width the solver has not is refused by the run, named
    with pytest.raises(ValueError, match="fall run: lanes must be 0"):
        runner._core().run_fall(runner.model(short["model"]), lanes=2, steps=1)


def test_csv_floats_round_trip(short, tmp_path):
    rows = runner.run_chunk(short, [3])
    out = tmp_path / "one.csv"
    w = csv_rows.Writer(str(out), runner.columns(short))
    w.write(rows)
    w.close()
    with open(out) as f:
        back = list(csv.DictReader(f))[0]
    for c, v in rows[0].items():
        if isinstance(v, float):
            assert float(back[c]) == v or (math.isnan(v) and back[c] == "nan"), c
        else:
            assert back[c] == str(v), c


def test_resume_skips_done_and_equals_an_uninterrupted_run(short_path, tmp_path):
    full, part = str(tmp_path / "full.csv"), str(tmp_path / "part.csv")
    assert batch("run", short_path, "--runs", "0:5", "--out", full, "--workers", "1")[0] == 0
    code, _, err = batch("run", short_path, "--runs", "0:3", "--out", part, "--workers", "1")
    assert code == 0, err
    with open(part, "a") as f:  # a run killed while writing its row
        f.write("3,-0.2,0.0")
    code, _, err = batch("run", short_path, "--runs", "0:5", "--out", part, "--workers", "1")
    assert code == 0, err
    assert "2 runs written, 3 already there" in err
    with open(full) as a, open(part) as b:
        assert b.read() == a.read()
    code, _, err = batch("run", short_path, "--runs", "5", "--out", part, "--workers", "1")
    assert code == 0 and "0 runs written, 5 already there" in err


BAD = [
    ("push:\n  link: torso\n  size: big\n",
     'scenario: push.size: expected a number or a distribution, got "big"'),
    ("spawn:\n  pich: 0.1\n", "scenario: spawn.pich: unknown field"),
    ("spawn:\n  x: {uniform: [1.0]}\n", "scenario: spawn.x.uniform: expected [lo, hi]"),
    ("material:\n  restitution: {uniform: [0.0, 1.5]}\n",
     "scenario: material.restitution.uniform[1]: 1.5 is outside [0.0, 1.0]"),
    ("spawn:\n  yaw: {gauss: 1}\n", 'scenario: spawn.yaw: unknown distribution "gauss"'),
    ("world: stairz\n", 'scenario: world: no shipped world "stairz"'),
    ("push:\n  link: {choice: [torso, tail]}\n",
     'scenario: push.link: the model has no link "tail"'),
    ("seed: -3\n", "scenario: seed: expected an integer"),
    ("duration: [1]\n", "scenario: duration: expected a number of seconds"),
    ("lanes: 2\n",
     "scenario: lanes: expected 0 (float lanes, the widest, from 24 bodies), 1 (double rows)"),
    ("push: {link: torso\n", "not YAML"),
]


@pytest.mark.parametrize("text,message", BAD)
def test_bad_scenarios_name_the_field_and_exit_1(text, message, tmp_path, capsys):
    path = tmp_path / "bad.yaml"
    path.write_text(text)
    out = tmp_path / "out.csv"
    assert cli.main(["run", str(path), "--runs", "0:2", "--out", str(out), "--workers", "1"]) == 1
    err = capsys.readouterr().err
    assert message in err
    assert len(err.strip().splitlines()) == 1, err
    assert not out.exists()


def test_bad_scenario_exit_status_of_the_script(tmp_path):
    path = tmp_path / "bad.yaml"
    path.write_text(BAD[0][0])
    code, out, err = batch("run", str(path), "--out", str(tmp_path / "x.csv"))
    assert code == 1
    assert err.strip() == BAD[0][1]
    code, _, err = batch("run", str(path), "--runs", "5:2", "--out", str(tmp_path / "x.csv"))
    assert code == 1 and err.startswith("--runs:")


def test_report_writes_pngs_and_counts(short, tmp_path):
    cols = runner.columns(short)
    base = runner.run_chunk(short, [0])[0]
    classes = ["supine", "prone", "prone", "side", "upright", "other", "supine", "prone"]
    rows = []
    for i, cls in enumerate(classes):
        r = dict(base, index=i, rest_class=cls, hic15=float(100 * (i + 1)),
                 push_size=float(10 + i), nan=int(i in (2, 5)),
                 broken_joints="neck;wrist_l" if i == 4 else ("wrist_l" if i == 6 else ""),
                 time_to_rest=float("nan") if i == 7 else 1.5)
        rows.append(r)
    path = str(tmp_path / "results.csv")
    w = csv_rows.Writer(path, cols)
    w.write(rows[::-1])  # in any order
    w.close()
    out = str(tmp_path / "rep")
    code, stdout, err = batch("report", path, "--out", out)
    assert code == 0, err
    for name in ("hic_histogram.png", "push_vs_hic.png", "rest_heatmap.png"):
        p = os.path.join(out, name)
        with open(p, "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n", name
        assert os.path.getsize(p) > 5000, name
    md = open(os.path.join(out, "summary.md")).read()
    assert "- runs: 8 (indices 0..7)" in md
    assert "- NaN runs: 2 (indices 2, 5)" in md
    assert "| supine | 2 | 25.0 % |" in md
    assert "| prone | 3 | 37.5 % |" in md
    assert "| upright | 1 | 12.5 % |" in md
    assert "- runs with a broken joint: 2" in md
    assert "- wrist_l: 2" in md and "- neck: 1" in md
    assert "- at rest by the end: 5 of 6" in md
    # HIC15 of the 6 runs without NaN: 100, 200, 400, 500, 700, 800
    assert "- HIC15 above 250: 4 runs" in md
    assert "| HIC15 | " in md and "| 800 |" in md
    df = report.read_results(path)
    assert list(df["index"]) == list(range(8))


def test_fall_recorder_on_a_scene():
    import ragdoll_sim
    scene = ragdoll_sim.Scene()
    model = runner.model(os.path.join(ROOT, "urdf", "ragdoll.urdf"))
    scene.spawn("r", model, position=(0, 0, 0.3), rpy=(0, -math.pi / 2, 0))  # on its back
    rec = ragdoll_sim.FallRecorder(scene, "r")
    rec.run(scene, 800)
    f = rec.record(scene)
    assert f.rest_class == "supine"
    assert f.links == model.link_names and len(f.peak_contact_force) == len(f.links)
    assert 0 < f.time_to_rest < 0.8 and not f.nan and f.broken_joints == []
    with pytest.raises(ValueError, match="no ragdoll 'nobody'"):
        ragdoll_sim.FallRecorder(scene, "nobody")
    d = ragdoll_sim.FallRecordDef()
    d.torso_link = "chest"
    with pytest.raises(ValueError, match="'chest' \\(torso_link\\)"):
        ragdoll_sim.FallRecorder(scene, "r", d)
