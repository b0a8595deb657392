"""The holdup of a flight (lifter) against its angular position, beside the geometric model of
Schofield and Glikin (1977): the material in a flight has a free surface through the flight's tip
at the angle gamma from the horizontal with

    tan(gamma) = [mu + Fr (cos(theta) - mu sin(theta))] / [1 - Fr (sin(theta) + mu cos(theta))],

Fr = omega^2 R_tip / g (R_tip = R - h, the tip's radius), theta the flight's angle from the
horizontal on the rising side, mu = tan of the material's dynamic angle of repose. For a radial
flight, the holdup is the wedge between the flight and that surface, from the tip out to the
shell: zero once gamma <= theta (the flight is empty).

The DEM holdup of a flight: the particles whose centre lies outside the tip circle (rho > R - h),
ahead of the flight (on its leading face's side) by less than half the flights' spacing, and that
move with the drum (speed relative to the shell's rigid turn below a quarter of the shell speed),
averaged over all flights and over the frames of the sampled revolutions, in bins of the flight's
angle. mu comes from the same material in the same drum without lifters (its dynamic angle of
repose by the surface fit, at --mu-omega, in the rolling regime), so the model gets nothing from
the lifter runs. A stricter count (relative speed below a tenth of the shell speed) shows how much
of the holdup is material sliding slowly over the pile.

    ./drumlab python app/python/examples/lifter_holdup.py [--omega 2 4] [--quick] [--out DIR]
"""
import argparse
import csv
import math
import pathlib

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import drumlab

root = pathlib.Path(__file__).resolve().parents[3]
parser = argparse.ArgumentParser()
parser.add_argument("--scene", default=str(root / "scenes/lifter_drum.toml"))
parser.add_argument("--omega", type=float, nargs="+", default=[2.0, 4.0], help="rad/s")
parser.add_argument("--revolutions", type=float, default=2.0, help="sampled, after one to fill")
parser.add_argument("--frames", type=int, default=200, help="frames per revolution")
parser.add_argument("--threads", type=int, default=1)
parser.add_argument("--mu-omega", type=float, default=1.0,
                    help="rad/s of the plain drum (rolling) that gives the material's mu")
parser.add_argument("--quick", action="store_true", help="a short check, not a measurement")
parser.add_argument("--out", default="holdup")
args = parser.parse_args()
out = pathlib.Path(args.out)
out.mkdir(parents=True, exist_ok=True)

base = drumlab.Scene.load(args.scene)
if args.quick:
    args.revolutions = 0.15
    args.frames = 40
    args.omega = args.omega[:1]
R = 0.5 * base["drum.diameter"]
depth = base["drum.depth"]
flight = base["wall"]["lifters"][0]
h = flight["height"]
count = int(flight.get("count", 4))
phase = math.radians(flight.get("phase_deg", 0.0))
length = flight.get("length", 0.0) or depth
thickness = flight.get("thickness", 0.0) or h / 8
rho_s = base["material.density"]
g = 9.81
spacing = 2 * math.pi / count


def wrap(a):
    """An angle in [-pi, pi)."""
    return (a + math.pi) % (2 * math.pi) - math.pi


def shorten(scene):
    """--quick: a smaller bed, a short settling (a check that the script runs, not a result)."""
    scene["fill.count"] = 1500
    scene["fill.settle_time"] = 0.05


def dynamic_angle_of_repose(omega):
    """The bed's angle by the surface fit, in the drum without lifters (degrees)."""
    scene = drumlab.Scene.load(args.scene)
    scene["drum.omega"] = omega
    text = scene.text()
    start = text.index("[[wall.lifters]]")
    end = text.find("\n[", start + 1)
    (out / "plain.toml").write_text(text[:start] + (text[end + 1:] if end >= 0 else ""))
    plain = drumlab.Scene.load(str(out / "plain.toml"))
    if args.quick:
        shorten(plain)
    sim = drumlab.Simulation(plain, threads=args.threads)
    sim.settle()
    sim.run(revolutions=0.5 if not args.quick else 0.05)
    angles = []
    sim.run(revolutions=0.5 if not args.quick else 0.05, every=max(1, int(2 * math.pi / omega / sim.dt / 50)),
            callback=lambda s: angles.append(s.observables()["angle_fit_deg"]))
    return float(np.nanmean(angles))


def model_holdup(theta, mu, fr, n=400):
    """Schofield-Glikin: the wedge's area between the flight (from the tip at angle theta) and the
    surface at gamma, inside the shell, times the flight's length, bulk density rho_s * 0.6."""
    num = mu + fr * (math.cos(theta) - mu * math.sin(theta))
    den = 1 - fr * (math.sin(theta) + mu * math.cos(theta))
    gamma = math.atan2(num, den)
    if gamma <= theta:
        return 0.0, math.degrees(gamma)
    tip = (R - h) * np.array([math.cos(theta), math.sin(theta)])
    # The wedge in polar coordinates about the tip: for each direction a in [theta, gamma], the
    # ray from the tip meets the shell at distance s(a); area = integral of s^2 / 2 da.
    a = np.linspace(theta, gamma, n)
    d = np.stack([np.cos(a), np.sin(a)], axis=1)
    b = d @ tip
    s = -b + np.sqrt(b * b - (tip @ tip - R * R))
    area = np.trapz(0.5 * s * s, a)
    return area * length * rho_s * 0.6, math.degrees(gamma)


bins = np.arange(-30.0, 181.0, 7.5)
centres = 0.5 * (bins[1:] + bins[:-1])
results = {}
mu = math.tan(math.radians(dynamic_angle_of_repose(args.mu_omega)))
for omega in args.omega:
    scene = drumlab.Scene.load(args.scene)
    scene["drum.omega"] = omega
    if args.quick:
        shorten(scene)
    sim = drumlab.Simulation(scene, threads=args.threads)
    sim.settle()
    sim.run(revolutions=1.0 if not args.quick else 0.1)  # the flights fill
    mass = np.zeros(len(centres))
    strict = np.zeros(len(centres))
    samples = np.zeros(len(centres))

    def sample(s):
        turned = s.revolutions * 2 * math.pi
        with s.arrays() as a:
            x, v, m = a.position, a.velocity, a.mass
            rho = np.hypot(x[:, 0], x[:, 1])
            phi = np.arctan2(x[:, 1], x[:, 0])
            shell = omega * np.stack([-x[:, 1], x[:, 0]], axis=1)  # the rigid turn's velocity
            slip = np.hypot(*(v[:, :2] - shell).T)
            moving = slip < 0.25 * abs(omega) * R
            still = slip < 0.1 * abs(omega) * R
            outer = rho > R - h
            for k in range(count):
                theta = wrap(phase + k * spacing + turned)
                ahead = wrap(phi - theta)
                face = 0.5 * thickness / np.maximum(rho, 1e-12)
                held = outer & moving & (ahead > face) & (ahead < 0.5 * spacing)
                b = np.searchsorted(bins, math.degrees(theta)) - 1
                if 0 <= b < len(centres):
                    mass[b] += m[held].sum()
                    strict[b] += m[held & still].sum()
                    samples[b] += 1
        return True

    every = max(1, int(2 * math.pi / abs(omega) / sim.dt / args.frames))
    sim.run(revolutions=args.revolutions, every=every, callback=sample)
    dem = np.where(samples > 0, mass / np.maximum(samples, 1), np.nan)
    dem_strict = np.where(samples > 0, strict / np.maximum(samples, 1), np.nan)
    fr = omega * omega * (R - h) / g
    model = [model_holdup(math.radians(c), mu, fr) for c in centres]
    results[omega] = (fr, mu, dem, model)

    def empty_at(values):
        """The first bin centre from which the holdup stays below 1 % of the first bin's."""
        for k in range(len(values)):
            if all(v < 0.01 * values[0] for v in values[k:]):
                return centres[k]
        return float("nan")
    with open(out / f"holdup_omega{omega:g}.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["theta_deg", "dem_kg", "dem_strict_kg", "model_kg", "gamma_deg", "frames"])
        for c, d, ds, (mk, gd), n in zip(centres, dem, dem_strict, model, samples):
            w.writerow([f"{c:.2f}", f"{d:.5g}", f"{ds:.5g}", f"{mk:.5g}", f"{gd:.2f}", int(n)])
    print(f"omega = {omega:g} rad/s, Fr_tip = {fr:.3f}, mu = {mu:.3f} "
          f"(dynamic angle {math.degrees(math.atan(mu)):.1f} deg)")
    print(f"  empty from theta = {empty_at(dem):.1f} deg (DEM), "
          f"{empty_at([m for m, _ in model]):.1f} deg (model)")
    print("  theta  DEM (g)  strict (g)  model (g)  gamma")
    for c, d, ds, (mk, gd) in zip(centres, dem, dem_strict, model):
        print(f"  {c:6.1f} {1e3 * d:8.1f} {1e3 * ds:10.1f} {1e3 * mk:9.1f} {gd:6.1f}")

fig, ax = plt.subplots(figsize=(7, 4.5))
for omega, (fr, mu, dem, model) in results.items():
    line, = ax.plot(centres, 1e3 * dem, "o-", ms=3, label=f"DEM, omega = {omega:g} rad/s (Fr = {fr:.2f})")
    ax.plot(centres, [1e3 * m for m, _ in model], "--", color=line.get_color(),
            label=f"Schofield-Glikin, mu = {mu:.2f}")
ax.set_xlabel("flight angle from the horizontal, rising side (deg)")
ax.set_ylabel("holdup of one flight (g)")
ax.set_title(f"{count} straight flights, h/R = {h / R:.2f}")
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(out / "holdup.png", dpi=120)
print("written", out / "holdup.png")
