"""The benchmark's scripts on made-up inputs: bench_report.py's ratio table (sleeping off and on,
the faster of Bullet and ODE, ours with lanes=1 beside the default float lanes), the issue's bars,
the flop section and the two-thread handoffs by round; bench_compare_report.py's table;
bench_compare.sh with two fake binaries (alternation, options, thread counts, handoffs);
bench.sh's engines of ours against the report's. No timing, no engine: each test runs in well
under a second.
"""
import os
import re
import stat
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
SCRIPTS = os.path.join(ROOT, "scripts")
sys.path.insert(0, SCRIPTS)

import bench_compare_report  # noqa: E402
import bench_ratios  # noqa: E402
import bench_report  # noqa: E402


def line(engine, scene, sps, rnd, bodies=480, sleep=0, n=None, **extra):
    fields = {"engine": engine, "scenario": scene, "ragdolls": n or 32, "bodies": bodies,
              "steps": 3000, "wall_s": 1, "steps_per_s": sps, "body_steps_per_s": sps * bodies,
              "us_per_body_step": 1e6 / (sps * bodies), "max_anchor_err_m": 0.0005,
              "max_ground_pen_m": 0.003, "max_limit_viol_rad": 0.01, "sleep": sleep,
              "round": rnd}
    fields.update(extra)
    return " ".join("%s=%s" % kv for kv in fields.items())


# Scene b in two rounds: ours sleeping off 1000 / 1200 steps/s, sleeping on 1100 / 1300;
# MuJoCo 100 / 150; Bullet 200 / 150; ODE 120 / 250 (the faster of the two: 200, then 250).
RAW = "\n".join([
    "# meta own_threads=2",
    "# meta flops_per_body_step=1000",
    "# meta flops_f64_per_body_step=600",
    "# meta flops_f32_per_body_step=8",
    "# meta flops_v128_per_body_step=90",
    "# meta flops_v256_per_body_step=4",
    "# meta peak_gflops=100.0",
    "# meta peak_gflops_float=200.0",
    "# meta peak_basis=2_cores_x_2000_MHz_x_25_DP_flops/cycle",
    line("ragdoll_sim", "b", 1000, 1),
    line("ragdoll_sim_sleep", "b", 1100, 1, sleep=1),
    line("mujoco-2.2.2", "b", 100, 1),
    line("bullet-3.24", "b", 200, 1),
    line("ode-0.16", "b", 120, 1),
    line("ragdoll_sim", "b", 1200, 2),
    line("ragdoll_sim_sleep", "b", 1300, 2, sleep=1),
    line("mujoco-2.2.2", "b", 150, 2),
    line("bullet-3.24", "b", 150, 2),
    line("ode-0.16", "b", 250, 2),
    # an old raw file: ours with sleep=1 under its own name is the sleeping-on engine
    line("ragdoll_sim", "c", 500, 1, sleep=1),
    line("mujoco-2.2.2", "c", 100, 1),
    # scene g: one thread costs 1.0, 1.4 and 1.0 us per body-step at N = 4, 16, 64 (mean 1.133,
    # N = 16 +24 %), two threads 1.8x one thread at N = 16
    line("ragdoll_sim_1thread", "g", 1e6 / 60, 1, bodies=60, n=4),
    line("ragdoll_sim_1thread", "g", 1e6 / 1.4 / 240, 1, bodies=240, n=16),
    line("ragdoll_sim_1thread", "g", 1e6 / 960, 1, bodies=960, n=64),
    line("ragdoll_sim", "g", 1.8e6 / 1.4 / 240, 1, bodies=240, n=16),
    "# FAILED engine=mujoco scenario=g ragdolls=16 round=1 rc=1 reason=x",
]) + "\n"


def make_report(tmp_path, raw=RAW):
    path = tmp_path / "raw.txt"
    path.write_text(raw)
    meta, runs, failures = bench_report.parse(str(path))
    return bench_report.report(meta, runs, failures, "scaling.png")[0]


def table_row(text, first_cell):
    rows = [l for l in text.splitlines() if l.startswith("| %s |" % first_cell)]
    assert rows, first_cell
    return [c.strip() for c in rows[0].strip("|").split("|")]


def test_ratio_table_sleep_off_and_on(tmp_path):
    text = make_report(tmp_path)
    assert "| scene | ours ÷ mujoco-2.2.2, sleep off | sleep on | ours ÷ bullet-3.24, sleep off" in text
    assert "ours ÷ the faster of bullet-3.24 and ode-0.16, sleep off | sleep on |" in text
    b = table_row(text, "b")
    # medians 1100 / 125 = 8.80; per round 10.00 and 8.00
    assert b[1] == "8.80 (8.00–10.00)"
    assert b[2] == "9.60 (8.67–11.00)"  # sleeping on: 1200 / 125; 11.00 and 8.67
    # the faster of Bullet and ODE: 200 then 250 (median 225): 1100 / 225 = 4.89; 5.00, 4.80
    assert b[7] == "4.89 (4.80–5.00)"
    assert b[8] == "5.33 (5.20–5.50)"
    c = table_row(text, "c")
    assert c[1] == "-" and c[2] == "5.00 (5.00–5.00)"


def test_bars(tmp_path):
    text = make_report(tmp_path)
    assert ("- b: ours ÷ mujoco-2.2.2 ≥ 8x: sleep off 8.80 (8.00–10.00), met; "
            "sleep on 9.60 (8.67–11.00)") in text
    assert "- b: ours ÷ the faster of bullet-3.24 and ode-0.16 ≥ 6x: sleep off 4.89 (4.80–5.00), not met" in text
    assert "- c: ours ÷ mujoco-2.2.2" not in text  # no sleeping-off run of c
    assert ("- one thread, cost per body-step for N = 4, 16, 64: mean 1.133 µs, largest "
            "deviation +24 % (N = 16); bar ±30 %: met") in text
    assert "- 2 threads ÷ one thread, N = 16: 1.80 (1.80–1.80); bar ≥ 1.7x: met" in text


def test_sync_by_round(tmp_path):
    raw = ("# meta sync_round_2=region_us=1.240 barrier_us=0.300\n"
           "# meta sync_round_1=region_us=0.435 barrier_us=0.024\n" + RAW)
    text = make_report(tmp_path, raw)
    assert ("(an empty parallel region / a TeamBarrier wait, µs; `bench_ragdoll sync`): "
            "round 1 0.435 / 0.024, round 2 1.240 / 0.300.") in text
    assert "TeamBarrier" not in make_report(tmp_path)  # an older raw file has none
    assert "two-thread ceiling" not in text  # nor a ceiling before the probe timed the cores
    raw = ("# meta sync_round_1=region_us=0.5 barrier_us=0.2 core0=0.83 core1=0.94 "
           "ceiling=1.77\n" + RAW)
    assert ("each thread's speed over one thread's alone, summed): round 1 1.77 (0.83 + 0.94). "
            "What two threads can gain over one on work that fits each core's cache"
            ) in make_report(tmp_path, raw)


def test_flops_section(tmp_path):
    text = make_report(tmp_path)
    assert "F64 600, F32 8, V128 90, V256 4" in text
    assert "100.0 GFLOP/s in double; in float 200.0 GFLOP/s, assuming 2 float" in text
    # scene b sleeping off only (the sleeping-on runs are left out)
    rows = [l for l in text.splitlines() if l.startswith("| b | 1000 |")]
    assert rows == ["| b | 1000 | 528000 | 0.53 | 0.53 % | 0.26 % |"]
    assert "The count is of the double rows" not in text  # no flops_opts: not said
    text = make_report(tmp_path, RAW.replace("# meta own_threads=2",
                                             "# meta own_threads=2\n# meta flops_opts=sleep=0,lanes=1"))
    assert "options `sleep=0,lanes=1`" in text
    assert "The count is of the double rows (`lanes=1`): the float lanes solve the same rows" in text


# Ours with every row in double (lanes=1) beside the default engine: scene b 2000 / 2400 steps/s
# sleeping off, 2200 / 2600 sleeping on; scene g on one thread 0.5 us per body-step at every N,
# two threads 2x one thread at N = 16; and an ensemble of each engine.
RAW_LANES1 = RAW + "\n".join([
    line("ragdoll_sim_lanes1", "b", 2000, 1),
    line("ragdoll_sim_lanes1_sleep", "b", 2200, 1, sleep=1),
    line("ragdoll_sim_lanes1", "b", 2400, 2),
    line("ragdoll_sim_lanes1_sleep", "b", 2600, 2, sleep=1),
    line("ragdoll_sim_lanes1_1thread", "g", 1e6 / 0.5 / 60, 1, bodies=60, n=4),
    line("ragdoll_sim_lanes1_1thread", "g", 1e6 / 0.5 / 240, 1, bodies=240, n=16),
    line("ragdoll_sim_lanes1_1thread", "g", 1e6 / 0.5 / 960, 1, bodies=960, n=64),
    line("ragdoll_sim_lanes1", "g", 2e6 / 0.5 / 240, 1, bodies=240, n=16),
    "# ensemble scene=b opts=- copies=32 at_rest_3s=31 (vmax_3s <= 0.01) vmax_3s=0..0.02",
    "# ensemble scene=b opts=lanes=1 copies=32 at_rest_3s=30 (vmax_3s <= 0.01) vmax_3s=0..0.03",
]) + "\n"


def test_lanes1_engine(tmp_path):
    text = make_report(tmp_path, RAW_LANES1)
    assert "ragdoll_sim_lanes1 (steps/s)" not in text and "÷ ragdoll_sim_lanes1" not in text
    # the default engine's table is unchanged; lanes=1 gets one of its own below it
    assert text.count("| scene | ours ÷ mujoco-2.2.2, sleep off | sleep on |") == 1
    assert "| scene | ours lanes=1 ÷ mujoco-2.2.2, sleep off | sleep on |" in text
    rows = [l for l in text.splitlines() if l.startswith("| b | ")]
    assert [c.strip() for c in rows[0].strip("|").split("|")][1] == "8.80 (8.00–10.00)"
    b = [c.strip() for c in rows[1].strip("|").split("|")]
    # medians 2200 / 125 = 17.60 (20.00, 16.00); sleeping on 2400 / 125 = 19.20 (22.00, 17.33)
    assert b[1:3] == ["17.60 (16.00–20.00)", "19.20 (17.33–22.00)"]
    assert b[7] == "9.78 (9.60–10.00)"  # 2200 / 225; 10.00, 9.60
    assert ("- b: ours lanes=1 ÷ mujoco-2.2.2 ≥ 8x: sleep off 17.60 (16.00–20.00), met; "
            "sleep on 19.20 (17.33–22.00)") in text
    assert "- b: ours ÷ mujoco-2.2.2 ≥ 8x: sleep off 8.80 (8.00–10.00), met" in text
    assert ("- lanes=1, one thread, cost per body-step for N = 4, 16, 64: mean 0.500 µs, "
            "largest deviation +0 % (N = 4); bar ±30 %: met") in text
    assert "- lanes=1, 2 threads ÷ one thread, N = 16: 2.00 (2.00–2.00); bar ≥ 1.7x: met" in text
    assert "- 2 threads ÷ one thread, N = 16: 1.80 (1.80–1.80)" in text
    assert "| ours lanes=1 ÷ mujoco-2.2.2 (steps/s) |" in text
    assert table_row(text, "b (lanes=1)")[1:3] == ["-", "0"]  # extra fields: substeps, sleep
    assert table_row(text, "b (lanes=1, sleep on)")[2] == "1"
    ens = [l for l in text.splitlines() if l.startswith("| b (lanes=1) | 32 | 30 of 32")]
    assert ens and "| b | 32 | 31 of 32" in text


def test_bench_sh_engines_match_report():
    # bench.sh runs each engine of ours with the --opt that the report names it by
    text = open(os.path.join(SCRIPTS, "bench.sh")).read()
    decl = next(l for l in text.splitlines() if l.startswith("declare -A OURS_OPTS=("))
    opts = dict(re.findall(r'\[(\w+)\]="([^"]*)"', decl))
    assert opts == {v.off: v.opt for v in bench_ratios.OURS_VARIANTS}
    assert opts == {"ragdoll_sim": "", "ragdoll_sim_lanes1": "lanes=1"}
    default = re.search(r'^ENGINES="\$\{ENGINES:-([^}]*)\}"', text, re.M).group(1).split()
    assert all(e in default for e in opts)


COMPARE_RAW = "\n".join([
    "# meta old_bin=/o", "# meta new_bin=/n", "# meta new_opts=lanes=1", "# meta rounds=2",
    line("ragdoll_sim", "p", 100, 1, side="old", label="p", run_threads=1),
    line("ragdoll_sim", "p", 150, 1, side="new", label="p", run_threads=1, max_ground_pen_m=0.004),
    line("ragdoll_sim", "p", 120, 2, side="new", label="p", run_threads=1, max_ground_pen_m=0.004),
    line("ragdoll_sim", "p", 100, 2, side="old", label="p", run_threads=1),
    line("ragdoll_sim", "g", 1000, 1, side="old", label="g1", run_threads=1, state_hash="ab"),
    line("ragdoll_sim", "g", 1100, 1, side="new", label="g1", run_threads=1, state_hash="ab"),
    line("ragdoll_sim", "c", 1000, 1, side="old", label="c", run_threads=1, state_hash="ab"),
    line("ragdoll_sim", "c", 1100, 1, side="new", label="c", run_threads=1, state_hash="cd"),
    "# FAILED side=new label=b run_threads=2 round=1 rc=139 reason=x",
]) + "\n"


def test_compare_table():
    meta, runs, failures = bench_compare_report.parse(COMPARE_RAW.splitlines())
    text = bench_compare_report.report(meta, runs, failures)
    assert "new: `/n` --opt lanes=1" in text
    p = table_row(text, "p")
    assert p[:6] == ["p", "1", "100 (100–100)", "135 (120–150)", "1.35 (1.20–1.50)", "≥ 1.35: met"]
    assert p[6:8] == ["0.0005 / 0.003 / 0.01", "0.0005 / 0.004 / 0.01"]
    g = table_row(text, "g N=1")
    assert g[4:6] == ["1.10 (1.10–1.10)", "≥ 1.20: not met"]
    assert g[8] == "yes" and table_row(text, "c")[8] == "no" and p[8] == "-"
    b = table_row(text, "b")
    assert b[2:5] == ["-", "-", "-"] and b[9] == "1"


FAKE = """#!/bin/bash
echo "$(basename "$0") $*" >> "%s"
echo "$0" >> "%s.paths"
[[ "$1" == sync ]] &&
  { echo "region_us=0.4 barrier_us=0.05 core0=0.9 core1=0.85 ceiling=1.75"; exit 0; }
sps=1000; [[ "$0" == *new* ]] && sps=1500
echo "engine=ragdoll_sim scenario=$1 steps_per_s=$sps max_anchor_err_m=0 max_ground_pen_m=0 max_limit_viol_rad=0"
"""


def test_compare_script_alternates_and_passes_options(tmp_path):
    log = tmp_path / "calls.txt"
    bins = []
    for name in ("old_bench", "new_bench"):
        b = tmp_path / name
        b.write_text(FAKE % (log, log))
        b.chmod(b.stat().st_mode | stat.S_IXUSR)
        bins.append(str(b))
    env = dict(os.environ, SCENES="b g1", THREADS="1 2", NEW_OPTS="lanes=1", OPTS="substeps=3",
               STEPS="7", OUT_RAW=str(tmp_path / "raw.txt"), OUT_MD=str(tmp_path / "t.md"),
               URDF="u.urdf")
    out = subprocess.run([os.path.join(SCRIPTS, "bench_compare.sh"), bins[0], bins[1], "2"],
                         env=env, capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    calls = log.read_text().splitlines()
    base = "--urdf u.urdf --opt sleep=0,threads=%d --steps 7 --opt substeps=3"
    assert calls == [
        "new_bench sync --urdf u.urdf",  # the handoffs and the ceiling before each round
        "old_bench b " + base % 1, "new_bench b " + base % 1 + " --opt lanes=1",
        "old_bench b " + base % 2, "new_bench b " + base % 2 + " --opt lanes=1",
        "old_bench g --urdf u.urdf --opt sleep=0,threads=1 --ragdolls 1 --steps 7 --opt substeps=3",
        "new_bench g --urdf u.urdf --opt sleep=0,threads=1 --ragdolls 1 --steps 7 --opt substeps=3 --opt lanes=1",
        # round 2: new first
        "new_bench sync --urdf u.urdf",
        "new_bench b " + base % 1 + " --opt lanes=1", "old_bench b " + base % 1,
        "new_bench b " + base % 2 + " --opt lanes=1", "old_bench b " + base % 2,
        "new_bench g --urdf u.urdf --opt sleep=0,threads=1 --ragdolls 1 --steps 7 --opt substeps=3 --opt lanes=1",
        "old_bench g --urdf u.urdf --opt sleep=0,threads=1 --ragdolls 1 --steps 7 --opt substeps=3",
    ]
    assert (tmp_path / "t.md").read_text() in out.stdout
    # every timed run is of a copy made for its round, not of the given file; the copies are gone
    paths = (tmp_path / "calls.txt.paths").read_text().splitlines()
    runs = [p for p, c in zip(paths, calls) if " sync" not in c]
    assert len(paths) == len(calls) and len(runs) == 12 and not set(runs) & set(bins)
    assert all(os.path.dirname(p).endswith(("/old", "/new")) for p in runs)
    assert not (tmp_path / "binaries").exists()
    assert "`bench_ragdoll sync`): round 1 0.4 / 0.05, round 2 0.4 / 0.05." in out.stdout
    assert "summed): round 1 1.75 (0.9 + 0.85), round 2 1.75 (0.9 + 0.85)." in out.stdout
    assert "| b | 2 | 1,000 (1,000–1,000) | 1,500 (1,500–1,500) | 1.50 (1.50–1.50) |" in out.stdout
    assert "| g N=1 | 1 | 1,000 (1,000–1,000) | 1,500 (1,500–1,500) | 1.50 (1.50–1.50) | ≥ 1.20: met |" in out.stdout


def test_fresh_copies_empties_the_folder_and_copies(tmp_path):
    for name, text in (("a_bin", "A"), ("b_bin", "B")):
        (tmp_path / name).write_text(text)
    dest = tmp_path / "copies"
    dest.mkdir()
    (dest / "stale").write_text("old round")
    cmd = 'source "%s"; fresh_copies "%s" "%s" "%s"' % (
        os.path.join(SCRIPTS, "env.sh"), dest, tmp_path / "a_bin", tmp_path / "b_bin")
    out = subprocess.run(["bash", "-c", cmd], capture_output=True, text=True, timeout=30)
    assert out.returncode == 0, out.stderr
    assert sorted(os.listdir(dest)) == ["a_bin", "b_bin"]
    assert (dest / "b_bin").read_text() == "B"


def test_bench_sh_times_the_round_copies():
    # every binary run_one times is a copy made for its round, made before the round's runs
    text = open(os.path.join(SCRIPTS, "bench.sh")).read()
    start = text.index("run_one() {")
    body = text[start:text.index("\n}\n", start)]
    bins = re.findall(r'\bbin="([^"]*)"', body)
    assert len(bins) == 4 and all(b.startswith("$ROUND_BINS/") for b in bins)
    loop = text[text.index('for r in $(seq "$ROUNDS"); do'):]
    assert loop.index("copy_round_binaries") < loop.index("run_one")
    assert '"$ROUND_BINS/bench_ragdoll" sync' in loop
