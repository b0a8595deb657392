"""The examples run (shortened) and write their charts."""
import os
import subprocess
import sys

from conftest import BIN, EXAMPLES, SCENES


def run_example(name, *args, cwd):
    env = dict(os.environ, MPLBACKEND="Agg")
    r = subprocess.run([sys.executable, str(EXAMPLES / name), *map(str, args)], cwd=cwd,
                       capture_output=True, text=True, env=env)
    assert r.returncode == 0, r.stdout + r.stderr
    return r.stdout


def test_bond_sweep(tmp_path):
    out = run_example("bond_sweep.py", "--quick", "--out", tmp_path / "b.png", cwd=tmp_path)
    assert "Bond" in out
    assert (tmp_path / "b.png").stat().st_size > 1000


def test_converge(tmp_path):
    out = run_example("converge.py", "--quick", "--out", tmp_path / "c.png", cwd=tmp_path)
    assert "stopped after" in out
    assert (tmp_path / "c.png").stat().st_size > 1000


def test_series_psd(tmp_path, small_scene):
    r = subprocess.run([BIN, "run", str(small_scene), "--steps", "200", "--every", "100",
                        "--h5", str(tmp_path / "s.h5")], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    out = run_example("series_psd.py", tmp_path / "s.h5", "--out", tmp_path / "p.png",
                      cwd=tmp_path)
    assert "granules" in out
    assert (tmp_path / "p.png").stat().st_size > 1000


def test_lifter_holdup(tmp_path):
    out = run_example("lifter_holdup.py", "--quick", "--omega", "3", "--out", tmp_path / "h",
                      cwd=tmp_path)
    assert "Fr_tip" in out and "empty from" in out
    rows = (tmp_path / "h" / "holdup_omega3.csv").read_text().splitlines()
    assert rows[0].startswith("theta_deg,dem_kg")
    assert len(rows) > 20
    assert (tmp_path / "h" / "holdup.png").stat().st_size > 1000
