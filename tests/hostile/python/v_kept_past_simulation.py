# a view kept after `del sim; gc.collect()`: it keeps its Simulation, and reads the particles as they were
# Expected: accepted
import gc
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
z = sim.field("position").z
expected = z.copy()
del sim
gc.collect()
other = pbfengine.Simulation(log=None, log_level="warn")
other.domain(lo=(0, 0, 0), hi=(0.1, 0.1, 0.1))
other.kernel_radius(0.02)
other.timestep(0.001)
other.lattice(lo=(0.01, 0.01, 0.01), hi=(0.09, 0.09, 0.09), spacing=0.01)
other.fix("pbf", "pbf")
other.run(40)
assert numpy.array_equal(numpy.asarray(z), expected), "the view changed"
print(float(z.sum()))
