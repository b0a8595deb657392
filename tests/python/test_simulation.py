"""drumlab.Simulation against `drumlab run`: the same bits; the array context; callbacks."""
import numpy as np
import pytest

import drumlab
from conftest import run_cli


def test_a_run_from_python_is_bit_identical_to_drumlab_run(small_scene, tmp_path):
    code, out = run_cli("run", small_scene, "--steps", 300, "--threads", 1,
                        "--checkpoint", tmp_path / "cli.h5")
    assert code == 0, out
    sim = drumlab.Simulation(drumlab.Scene.load(str(small_scene)), threads=1)
    seen = []
    assert sim.run(steps=300, callback=lambda s: seen.append(s.steps), every=100) == 300
    assert len(seen) == 3
    sim.checkpoint(tmp_path / "py.h5")
    cli = drumlab.read_checkpoint(str(tmp_path / "cli.h5"))
    py = drumlab.read_checkpoint(str(tmp_path / "py.h5"))
    assert cli["steps"] == py["steps"]
    for name in ("position", "velocity", "omega", "radius", "id"):
        assert np.array_equal(cli[name], py[name]), name  # every bit


def test_views_equal_the_checkpoint_and_raise_after_their_block(small_scene, tmp_path):
    sim = drumlab.Simulation(drumlab.Scene.load(str(small_scene)), threads=1)
    sim.run(steps=50)
    sim.checkpoint(tmp_path / "c.h5")
    saved = drumlab.read_checkpoint(str(tmp_path / "c.h5"))
    with sim.arrays() as a:
        assert a.position.shape == (300, 3)
        assert np.array_equal(np.asarray(a.position), saved["position"])
        assert np.array_equal(np.asarray(a.velocity), saved["velocity"])
        assert np.array_equal(np.asarray(a.id), saved["id"])
        assert a.film.shape == (300,)
        assert float(np.sum(a.radius)) == pytest.approx(300 * 0.002)
        pos = a.position
        with pytest.raises(TypeError):
            pos[0] = [0.0, 0.0, 0.0]
        assert not np.asarray(pos).flags.writeable
        with pytest.raises(RuntimeError, match="arrays are open"):
            sim.run(steps=1)  # stepping would move the memory under the views
    with pytest.raises(RuntimeError, match="outside its"):
        np.asarray(pos)
    with pytest.raises(RuntimeError, match="outside its"):
        pos[0]
    with pytest.raises(RuntimeError, match="outside its"):
        a.velocity
    sim.run(steps=1)  # closed: stepping goes on


def test_a_callback_that_raises_stops_the_run_with_its_traceback(small_scene):
    sim = drumlab.Simulation(drumlab.Scene.load(str(small_scene)), threads=1)

    def boom(s):
        if s.steps > 0:
            raise ArithmeticError("stop here")

    start = None
    sim.settle()
    start = sim.steps
    with pytest.raises(ArithmeticError, match="stop here") as err:
        sim.run(steps=500, callback=boom, every=50)
    assert sim.steps == start + 50  # stopped after the first chunk
    assert "boom" in "".join(str(e.name) for e in err.traceback)
    # A callback returning False stops the run there, quietly.
    assert sim.run(steps=500, callback=lambda s: False, every=20) == 20


def test_setters_keep_the_invariants_and_analysis_reads_the_state(small_scene):
    sim = drumlab.Simulation(drumlab.Scene.load(str(small_scene)), threads=1)
    sim.run(steps=100)
    sim.set_velocity([0, 5], [[0.0, 0.1, 0.0], [0.0, 0.0, 0.0]])
    with sim.arrays() as a:
        row = int(np.nonzero(np.asarray(a.id) == 0)[0][0])
        assert np.array_equal(a.velocity[row], [0.0, 0.1, 0.0])
    with pytest.raises(ValueError, match="no particle with id"):
        sim.set_velocity([300], [[0.0, 0.0, 0.0]])
    with pytest.raises(ValueError, match="not finite"):
        sim.set_velocity([1], [[float("nan"), 0.0, 0.0]])
    obs = sim.observables()
    assert -90.0 <= obs["angle_com_deg"] <= 90.0
    agg = sim.agglomerates(criterion="components")
    assert agg["criterion"] == "components"
    assert sum(agg["sizes"]) == 300
    contacts = sim.contacts()
    assert contacts["pairs"].shape[1] == 2
    assert contacts["bridge_volume"].shape[0] == contacts["bond_pairs"].shape[0]
    assert np.all(contacts["bridge_volume"] >= 0.0)
    with pytest.raises(ValueError, match="criterion"):
        sim.agglomerates(criterion="clumps")


def test_law_curve_is_the_clis_law(small_scene, tmp_path):
    scene = drumlab.Scene.load(str(small_scene))
    curve = drumlab.law_curve(scene)
    assert curve["gap"].shape == curve["normal_force"].shape
    assert curve["normal_force"].min() < 0.0 < curve["normal_force"].max()  # bridge, then Hertz
    # The bridge breaks where the law says (within one probe position).
    step = np.max(np.abs(np.diff(curve["gap"])))
    assert abs(curve["rupture_gap"] - curve["predicted_rupture"]) <= 2 * step
    code, out = run_cli("law", small_scene, "--out", tmp_path / "law")
    assert code == 0, out
    rows = np.genfromtxt(tmp_path / "law" / "law.csv", delimiter=",", names=True, dtype=None,
                         encoding="utf-8")
    assert len(rows) == len(curve["gap"])
    assert np.allclose(rows["gap_or_overlap_m"], curve["gap"], rtol=1e-12, atol=0.0)
    assert np.allclose(rows["normal_force_N"], curve["normal_force"], rtol=1e-9, atol=1e-15)
