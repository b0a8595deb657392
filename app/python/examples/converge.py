"""A callback that stops a run once the angle of repose has converged: the mean over the last
window of samples moves by less than a tolerance from the window before.

    ./drumlab python app/python/examples/converge.py [--quick] [--out converge.png]
"""
import argparse
import pathlib

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import drumlab

root = pathlib.Path(__file__).resolve().parents[3]
parser = argparse.ArgumentParser()
parser.add_argument("--scene", default=str(root / "scenes/drum_demo.toml"))
parser.add_argument("--quick", action="store_true")
parser.add_argument("--tolerance", type=float, default=0.5, help="degrees")
parser.add_argument("--out", default="converge.png")
args = parser.parse_args()

scene = drumlab.Scene.load(args.scene)
if args.quick:
    scene["fill.count"] = 400
    scene["fill.settle_time"] = 0.05
sim = drumlab.Simulation(scene)
times, angles = [], []
window = 5


def converged(s):
    times.append(s.time)
    angles.append(s.observables()["angle_com_deg"])
    if len(angles) < 2 * window:
        return True  # go on
    last, before = np.mean(angles[-window:]), np.mean(angles[-2 * window:-window])
    return abs(last - before) >= args.tolerance  # False stops the run


steps = sim.run(revolutions=0.1 if args.quick else 2.0, callback=converged, every=100)
print(f"stopped after {steps} steps ({sim.revolutions:.3f} revolutions): "
      f"angle {np.mean(angles[-window:]):.1f} deg")
plt.plot(times, angles, marker=".")
plt.xlabel("time (s)")
plt.ylabel("angle of repose (centre of mass), deg")
plt.savefig(args.out, dpi=100)
print(f"chart {args.out}")
