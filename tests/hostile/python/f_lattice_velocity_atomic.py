# a lattice refused for its velocity function leaves the particles as they were
# Expected: refused, Error: lattice && velocity function
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.domain(lo=(0, 0, 0), hi=(0.1, 0.1, 0.1))
sim.kernel_radius(0.02)
sim.timestep(0.001)
sim.lattice(lo=(0.02, 0.02, 0.02), hi=(0.06, 0.06, 0.06), spacing=0.01)  # 64 particles
sim.fix("gravity", "gravity")
sim.fix("pbf", "pbf")
sim.fix("walls", "box")
try:
    sim.lattice(lo=(0.07, 0.07, 0.07), hi=(0.09, 0.09, 0.09), spacing=0.01, velocity=lambda x, y, z: 1 / 0)
finally:
    assert sim.count == 64, f"the refused lattice left {sim.count - 64} particles"
