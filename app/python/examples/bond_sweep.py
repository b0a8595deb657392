"""A Bond-number sweep: the dynamic angle of repose of a wet drum against the surface tension
(the Bond number is the capillary force over the weight), plotted with matplotlib.

    ./drumlab python app/python/examples/bond_sweep.py [--quick] [--out bond_sweep.png]
"""
import argparse
import math
import pathlib

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import drumlab

root = pathlib.Path(__file__).resolve().parents[3]
parser = argparse.ArgumentParser()
parser.add_argument("--scene", default=str(root / "scenes/granulation_small.toml"))
parser.add_argument("--quick", action="store_true", help="two tensions, a short run (tests)")
parser.add_argument("--out", default="bond_sweep.png")
args = parser.parse_args()

tensions = [0.005, 0.072] if args.quick else [0.005, 0.01, 0.02, 0.04, 0.072]
revolutions = 0.02 if args.quick else 0.5
bond, angle, spread = [], [], []
for gamma in tensions:
    scene = drumlab.Scene.load(args.scene)
    scene["liquid.surface_tension"] = gamma
    if args.quick:
        scene["fill.count"] = 300
        scene["fill.settle_time"] = 0.02
    sim = drumlab.Simulation(scene)
    samples = []
    sim.run(revolutions=revolutions, every=200,
            callback=lambda s: samples.append(s.observables()["angle_com_deg"]))
    with sim.arrays() as a:
        r = float(np.mean(a.radius))
        m = float(np.mean(a.mass))
    weight = m * abs(scene["gravity"][1])
    bond.append(2.0 * math.pi * r * gamma / weight)  # capillary force of a bridge / weight
    half = samples[len(samples) // 2:]
    angle.append(np.mean(half))
    spread.append(np.std(half))
    print(f"surface tension {gamma:g} N/m: Bond {bond[-1]:.3g}, angle {angle[-1]:.1f} deg")

plt.errorbar(bond, angle, yerr=spread, marker="o", capsize=3)
plt.xlabel("Bond number (2 pi r gamma / m g)")
plt.ylabel("dynamic angle of repose (centre of mass), deg")
plt.title(f"{pathlib.Path(args.scene).stem}: angle against Bond number")
plt.savefig(args.out, dpi=100)
print(f"chart {args.out}")
