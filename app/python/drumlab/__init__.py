"""drumlab from Python: scenes, runs with callbacks, zero-copy views of the particles, analysis.

    import drumlab
    scene = drumlab.Scene.load("scenes/granulation_small.toml")
    scene["liquid.surface_tension"] = 0.05        # checked at once: ValueError if bad
    scene.fill.count = 200                        # the same, as attributes
    sim = drumlab.Simulation(scene, method="verlet:m2", threads=2)
    sim.run(revolutions=0.5, callback=lambda s: print(s.time), every=500)
    with sim.arrays() as a:                       # read-only numpy views, no copy
        print(a.position.shape, a.radius.mean())
    print(sim.observables()["angle_com_deg"])

The engine is the one `drumlab run` runs: a run driven from here gives the same bits. See
app/python/README.md.
"""
from ._drumlab import InputError, Scene, law_curve, read_checkpoint, read_series
from ._simulation import Arrays, Simulation, View
from . import _scene  # noqa: F401  (attribute access to a Scene's keys)

__all__ = ["Scene", "Simulation", "Arrays", "View", "InputError", "law_curve",
           "read_checkpoint", "read_series"]
