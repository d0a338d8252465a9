#!/usr/bin/env python3
"""bench_scene: the Python Scene's stepping cost on bench_ragdoll's scene a (one ragdoll
standing, pelvis at 1.5 m, dt 1 ms, ground friction as the Scene's default surface).

usage: bench_scene.py [--steps N] [--repeat R] [--no-injury] [--urdf FILE]
Prints one line: steps, us_per_step (best of R), the Scene's build and spawn time, the hash.
Run after `source .ws/devel/setup.bash` with /usr/bin/python3.
"""
import argparse
import pathlib
import time

import ragdoll_sim

URDF = pathlib.Path(__file__).resolve().parents[1] / "urdf" / "ragdoll.urdf"


def main():
    """Times Scene.step(steps) R times on fresh scenes and prints the best."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=10000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-injury", action="store_true", help="Scene(injury=False)")
    ap.add_argument("--urdf", default=str(URDF), help="the model (bench_ragdoll --urdf)")
    args = ap.parse_args()
    model = ragdoll_sim.Model.from_file(args.urdf)
    best, setup, h = float("inf"), float("inf"), 0
    for _ in range(args.repeat):
        t0 = time.perf_counter()
        scene = ragdoll_sim.Scene(dt=0.001, injury=not args.no_injury)
        scene.spawn("ragdoll", model, position=(0, 0, 1.5))
        t1 = time.perf_counter()
        scene.step(args.steps)
        t2 = time.perf_counter()
        best, setup, h = min(best, t2 - t1), min(setup, t1 - t0), scene.state_hash()
    print(f"bench_scene steps={args.steps} us_per_step={best / args.steps * 1e6:.2f} "
          f"setup_ms={setup * 1e3:.2f} state_hash={h:016x}")


if __name__ == "__main__":
    main()
