# a plain array (numpy.asarray of a view) kept after the Simulation is gone: it reads and writes the block it pinned, nobody else's
# Expected: accepted
import gc
import weakref
import numpy
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.domain(lo=(0, 0, 0), hi=(0.1, 0.1, 0.1))
sim.kernel_radius(0.02)
sim.timestep(0.001)
sim.lattice(lo=(0.02, 0.02, 0.02), hi=(0.06, 0.06, 0.06), spacing=0.01)  # 64 particles
sim.fix("gravity", "gravity")
sim.fix("pbf", "pbf")
sim.fix("walls", "box")
raw = numpy.asarray(sim.field("position", writable=True).z)
expected = raw.copy()
gone = weakref.ref(sim)
del sim
gc.collect()
assert gone() is None, "the Simulation lives on"
other = pbfengine.Simulation(log=None, log_level="warn")
other.domain(lo=(0, 0, 0), hi=(0.1, 0.1, 0.1))
other.kernel_radius(0.02)
other.timestep(0.001)
other.lattice(lo=(0.01, 0.01, 0.01), hi=(0.09, 0.09, 0.09), spacing=0.01)
other.fix("pbf", "pbf")
other.run(40)
assert numpy.array_equal(raw, expected), "the pinned block changed"
raw[:] = 1e30
other.run(1)
assert other.copy("position").max() < 0.1, "a write reached another Simulation"
