"""app/bench/paper_deep_packing.py: the dense packing that makes the Table 2 drum's rolling state
reachable, on a small drum of the same three classes."""
import pathlib
import subprocess
import sys

import numpy as np

from conftest import BIN

SCRIPT = pathlib.Path(__file__).parents[2] / "app/bench/paper_deep_packing.py"

# The Table 2 scene's classes and law, 3,000 particles in a small drum (36 of its 96 blocks).
SCENE = """name = "packing_small"
gravity = [0.0, -9.81, 0.0]
search = "m5"

[drum]
diameter = 0.4
depth = 0.25
omega = 2.0
ends = "caps"

[[particles]]
name = "small"
radius = 0.005
volume_fraction = 0.3333333333333333

[[particles]]
name = "medium"
radius = 0.010
volume_fraction = 0.3333333333333333

[[particles]]
name = "large"
radius = 0.015
volume_fraction = 0.3333333333333334

[material]
density = 2500.0
youngs_modulus = 5.0e6
poisson_ratio = 0.3
restitution = 0.5
friction = 0.5

[fill]
kind = "random"
count = 3000
volume_fraction = 0.35
seed = 1
settle_time = 0.0

[time]
dt_factor = 0.2
revolutions = 0.01

[output]
directory = "out/packing_small"
"""


def test_packing_has_the_scenes_classes_no_overlap_and_runs(tmp_path):
    scene = tmp_path / "small.toml"
    scene.write_text(SCENE)
    out = tmp_path / "packed"
    r = subprocess.run([sys.executable, str(SCRIPT), str(out), "--scene", str(scene),
                        "--settle-time", "0.002"], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    xyzr = np.loadtxt(out / "packing.csv", delimiter=",", skiprows=1)
    # The fill's split by volume: 216 : 27 : 8 particles of r : 2r : 3r.
    radii, counts = np.unique(xyzr[:, 3], return_counts=True)
    assert list(radii) == [0.005, 0.010, 0.015]
    assert counts.sum() == 3000
    assert np.allclose(counts / counts.sum(), np.array([216, 27, 8]) / 251, atol=2e-3)
    # Nothing overlaps: the smallest gap is positive (the lattice leaves 1 % of a diameter).
    p, rad = xyzr[:, :3], xyzr[:, 3]
    for a in range(0, len(p), 250):
        b = min(a + 250, len(p))
        gap = np.linalg.norm(p[a:b, None, :] - p[None, :, :], axis=2) - (rad[a:b, None] + rad)
        gap[np.arange(b - a), np.arange(a, b)] = np.inf
        assert gap.min() > 0.0
    # Inside the drum (axis along z, centred on x = y = 0) and lowest first: the lower half.
    assert (np.hypot(p[:, 0], p[:, 1]) + rad <= 0.2).all()
    assert (p[:, 2] - rad >= 0).all() and (p[:, 2] + rad <= 0.25).all()
    assert np.median(p[:, 1]) < 0.0
    text = (out / "scene.toml").read_text()
    assert 'kind = "file"' in text and 'search = "verlet:mlgrid"' in text
    # drumlab takes the packing: it settles and turns a few steps from it.
    r = subprocess.run([BIN, "run", str(out / "scene.toml"), "--steps", "20"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "3000" in r.stdout.replace(",", "")
