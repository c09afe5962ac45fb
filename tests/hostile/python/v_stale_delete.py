# a view used after delete() removed half the particles
# Expected: refused, StaleViewError: 'position[2]' && taken at step 0 && field('position')
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
sim.delete(region="box", lo=(0, 0, 0), hi=(0.1, 0.1, 0.04))
z[0]
