"""A dense packing of scenes/paper_drum_deep.toml's particles, so its rolling state is reachable.

The scene's random fill places 2.6 M particles at solid fraction 0.35 in the lower ~70 % of the
drum; settling that loose fill is a fall of most of a metre that the scene's time step does not
carry, and a random fill cannot place them denser (random sequential addition jams near 0.38).
This writes the same particles (the same class counts as the scene's fill) on lattices instead,
at solid fraction 0.51, in the lower half of the drum, so settling is a short compaction:

* the drum's lower cross-section is cut into cubic blocks of 6 small diameters (plus 1 % slack),
  the same blocks along the axis;
* each block holds one class only: 216 small, 27 medium or 8 large particles on a simple cubic
  lattice (the three classes fill a block with the same solid volume, so equal-volume classes
  take equal numbers of blocks); blocks are given classes in random order, filled lowest first;
* each centre is jittered by at most 2e-5 m per axis, below half the smallest gap.

The scene's own search (`m5`, a grid searched every step) would settle at 0.6 steps/s, so the
copy names `--search` (default `verlet:mlgrid`).

It writes DIR/packing.csv (x,y,z,r in m, `[fill] kind = "file"`) and DIR/scene.toml (the scene
with that fill, its settle time and its output folder moved to DIR), for

    python3 app/bench/paper_deep_packing.py out/paper_deep_packed
    drumlab bench throughput --scene out/paper_deep_packed/scene.toml --turn 0.1 --threads 2 ...

The lattice leaves its trace: until the bed has been sheared, the blocks' cores hold fewer
contacts a particle than a random bed (state it beside any figure measured from it).
"""
import argparse
import pathlib
import re
import sys
import tomllib

import numpy as np

SLACK = 1.01  # lattice spacing over the diameter
JITTER = 2.0e-5  # m, per axis; the smallest gap between neighbours is 1e-4 m


def class_counts(classes, count):
    """The fill's split of `count` over the classes by volume fraction (engine/fill/random_fill.cpp)."""
    rmax = max(c["radius"] for c in classes)
    weight = [c["volume_fraction"] / (c["radius"] / rmax) ** 3 for c in classes]
    total = sum(weight)
    exact = [count * w / total for w in weight]
    counts = [int(round(e)) if abs(e - round(e)) < 1e-9 * max(1.0, e) else int(np.floor(e)) for e in exact]
    order = sorted(range(len(classes)), key=lambda c: -(exact[c] - np.floor(exact[c])))
    k = 0
    while sum(counts) < count:
        counts[order[k % len(order)]] += 1
        k += 1
    return counts


def block_slots(radius_drum, depth, edge):
    """Lower-left-front corners of the blocks inside the drum, lowest first (axis along z)."""
    n = int(np.floor(2 * radius_drum / edge))
    x0 = -0.5 * n * edge
    xs = x0 + edge * np.arange(n)
    gx, gy = np.meshgrid(xs, xs, indexing="ij")
    corners = [(gx, gy), (gx + edge, gy), (gx, gy + edge), (gx + edge, gy + edge)]
    inside = np.ones_like(gx, dtype=bool)
    for cx, cy in corners:
        inside &= cx * cx + cy * cy <= radius_drum * radius_drum
    xy = np.stack([gx[inside], gy[inside]], axis=1)
    xy = xy[np.lexsort((xy[:, 0], xy[:, 1]))]  # by height, then across
    layers = int(np.floor(depth / edge))
    z0 = 0.5 * (depth - layers * edge)
    zs = z0 + edge * np.arange(layers)
    # Lowest first: every layer of the axis at one height before the next height.
    slots = np.array([(x, y, z) for x, y in xy for z in zs])
    return slots


def lattice(edge, per_side):
    """Centres of a per_side^3 simple cubic lattice filling a block of this edge."""
    step = edge / per_side
    g = (np.arange(per_side) + 0.5) * step
    x, y, z = np.meshgrid(g, g, g, indexing="ij")
    return np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", type=pathlib.Path, help="folder for packing.csv and scene.toml")
    ap.add_argument("--scene", type=pathlib.Path, default=pathlib.Path("scenes/paper_drum_deep.toml"))
    ap.add_argument("--settle-time", type=float, default=0.1, help="s of settling in scene.toml")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--search", default="verlet:mlgrid", help="search method in scene.toml")
    ap.add_argument("--max-overlap", type=float, default=1.0,
                    help="time.max_overlap in scene.toml (the scene's default is 0.5)")
    a = ap.parse_args()

    text = a.scene.read_text()
    scene = tomllib.loads(text)
    classes = sorted(scene["particles"], key=lambda c: c["radius"])
    radii = [c["radius"] for c in classes]
    if len(classes) != 3 or not np.allclose([radii[1] / radii[0], radii[2] / radii[0]], [2, 3]):
        sys.exit(f"{a.scene}: particles: this packing needs three classes of radius r, 2r, 3r")
    counts = class_counts(classes, scene["fill"]["count"])
    per_side = [6, 3, 2]  # particles along a block's edge: small, medium, large
    per_block = [p**3 for p in per_side]
    edge = 6 * 2 * radii[0] * SLACK
    blocks = [-(-n // b) for n, b in zip(counts, per_block)]

    slots = block_slots(0.5 * scene["drum"]["diameter"], scene["drum"]["depth"], edge)
    need = sum(blocks)
    if need > len(slots):
        sys.exit(f"{a.scene}: {need} blocks needed, the drum holds {len(slots)}")
    rng = np.random.default_rng(a.seed)
    kinds = np.repeat(np.arange(3), blocks)
    rng.shuffle(kinds)
    corners = slots[:need]

    parts = []
    for c in range(3):
        mine = corners[kinds == c]
        local = lattice(edge, per_side[c])
        centres = (mine[:, None, :] + local[None, :, :]).reshape(-1, 3)[: counts[c]]
        parts.append(np.column_stack([centres, np.full(len(centres), radii[c])]))
    xyzr = np.concatenate(parts)
    xyzr[:, :3] += rng.uniform(-JITTER, JITTER, size=(len(xyzr), 3))

    a.out.mkdir(parents=True, exist_ok=True)
    csv = a.out / "packing.csv"
    tmp = csv.with_suffix(".csv.part")
    np.savetxt(tmp, xyzr, fmt="%.9g", delimiter=",", header="x,y,z,r", comments="")
    tmp.replace(csv)

    fill = (f'[fill]\nkind = "file"\nfile = "packing.csv"\nsettle_time = {a.settle_time!r}\n\n')
    out_text = re.sub(r"\[fill\]\n(?:[^\[]*\n)?(?=\[)", fill, text, count=1)
    out_text = re.sub(r'(\[output\][^\[]*?directory\s*=\s*)"[^"]*"', rf'\1"{a.out.resolve()}"', out_text)
    out_text = re.sub(r'^name = "([^"]*)"', r'name = "\1_packed"', out_text, count=1, flags=re.M)
    # The scene's m5 grid searches every step (0.6 steps/s at this size): settle on a Verlet list.
    out_text = re.sub(r'^search = "[^"]*"', f'search = "{a.search}"', out_text, count=1, flags=re.M)
    # E = 5 MPa under 1.2 m of bed: the bottom's contacts overlap up to 0.8 small radii.
    out_text = re.sub(r"^\[time\]\n", f"[time]\nmax_overlap = {a.max_overlap!r}\n", out_text,
                      count=1, flags=re.M)
    (a.out / "scene.toml").write_text(out_text)
    top = corners[:, 1].max() + edge
    solid = sum(n * 4 / 3 * np.pi * r**3 for n, r in zip(counts, radii))
    print(f"{len(xyzr)} particles ({', '.join(map(str, counts))}) in {need} blocks of {edge:.4f} m; "
          f"bed top {top:+.3f} m from the axis; solid {solid:.3f} m^3, fraction in the blocks "
          f"{solid / (need * edge**3):.3f}")
    print(f"wrote {csv} and {a.out / 'scene.toml'}")


if __name__ == "__main__":
    main()
