"""Shared by the Python module's tests: the drumlab executable, the shipped scenes, a small
scene written per test, and the CLI's run for comparisons."""
import os
import pathlib
import subprocess

import pytest

BIN = os.environ.get("DRUMLAB_BIN", str(pathlib.Path(__file__).parents[2] / "build/bin/drumlab"))
SCENES = pathlib.Path(os.environ.get("DRUMLAB_SCENES_DIR",
                                     pathlib.Path(__file__).parents[2] / "scenes"))
EXAMPLES = pathlib.Path(os.environ.get("DRUMLAB_EXAMPLES_DIR",
                                       pathlib.Path(__file__).parents[2] / "app/python/examples"))

# A small wet drum (liquid migration: films, bridges), 300 particles, a few hundred steps.
SMALL_WET = """name = "py_small"
description = "the Python tests' small wet drum"
gravity = [0.0, -9.81, 0.0]
search = "verlet:m2"

[drum]
diameter = 0.08
depth = 0.02
omega = 6.0

[[particles]]
name = "grain"
radius = 0.002
volume_fraction = 1.0

[material]
density = 2500.0
youngs_modulus = 5.0e6
poisson_ratio = 0.3
restitution = 0.5
friction = 0.4

[liquid]
surface_tension = 0.072
contact_angle_deg = 20
liquid_content = 0.02
max_bridge_volume = 2e-9

[fill]
count = 300
volume_fraction = 0.3
seed = 4
settle_time = 0.02

[time]
dt_factor = 0.2
duration = 0.02
"""


@pytest.fixture
def small_scene(tmp_path):
    path = tmp_path / "small.toml"
    path.write_text(SMALL_WET)
    return path


def run_cli(*args):
    """drumlab ARGS: (exit code, stdout + stderr)."""
    r = subprocess.run([BIN, *map(str, args)], capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr
