"""The Python module's overhead on the turning phase (one thread, the scene's own method):

1. the callback's cost: one Simulation turning alternately `--steps` steps without a callback
   and `--steps` steps with a callback every 100 steps (the same arrays in the same memory, so
   only the module's chunking, GIL hand-overs and the callback differ);
2. against `drumlab run --steps N` (its "stepping" seconds) in alternating rounds, a fresh
   Simulation each round. Run it on a quiet machine: anything else running (a test suite) moves
   either side by tens of per cent.

    ./drumlab python app/bench/python_overhead.py [SCENE] [--steps N] [--rounds R]
"""
import argparse
import pathlib
import re
import statistics
import subprocess
import time

import drumlab

root = pathlib.Path(__file__).resolve().parents[2]
parser = argparse.ArgumentParser()
parser.add_argument("scene", nargs="?", default=str(root / "scenes/granulation_small.toml"))
parser.add_argument("--steps", type=int, default=20000)
parser.add_argument("--rounds", type=int, default=5)
parser.add_argument("--bin", default=str(root / "build/bin/drumlab"))
args = parser.parse_args()

sim = drumlab.Simulation(drumlab.Scene.load(args.scene), threads=1)
sim.settle()
plain, called = [], []
for k in range(args.rounds):
    t0 = time.perf_counter()
    sim.run(steps=args.steps)
    plain.append(time.perf_counter() - t0)
    calls = []
    t0 = time.perf_counter()
    sim.run(steps=args.steps, callback=lambda s: calls.append(s.steps), every=100)
    called.append(time.perf_counter() - t0)
    print(f"round {k + 1}: without a callback {plain[-1]:.3f} s, with one every 100 steps "
          f"({len(calls)} calls) {called[-1]:.3f} s")
p, c = statistics.median(plain), statistics.median(called)
n = sim.n
print(f"callback every 100 steps: {c / p:.4f}x the run without ({n * args.steps / p / 1e6:.2f} "
      f"against {n * args.steps / c / 1e6:.2f} M particle-steps/s, medians of {args.rounds})")

cli, fresh = [], []
for k in range(args.rounds):
    out = subprocess.run([args.bin, "run", args.scene, "--steps", str(args.steps), "--threads",
                          "1"], capture_output=True, text=True, check=True).stdout
    cli.append(float(re.search(r"stepping ([0-9.e+-]+) s", out).group(1)))
    s = drumlab.Simulation(drumlab.Scene.load(args.scene), threads=1)
    s.settle()
    t0 = time.perf_counter()
    s.run(steps=args.steps, callback=lambda s: None, every=100)
    fresh.append(time.perf_counter() - t0)
print(f"drumlab run: {' '.join(f'{x:.3f}' for x in cli)} s; a fresh Simulation each round "
      f"(callback every 100 steps): {' '.join(f'{x:.3f}' for x in fresh)} s")
print(f"medians: Python / CLI = {statistics.median(fresh) / statistics.median(cli):.4f} "
      "(each process and each Simulation has its arrays elsewhere in memory; the first figure "
      "isolates the module's own cost)")
