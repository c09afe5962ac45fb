# a misspelt keyword of a fix
# Expected: refused, Error: fix 'g2' (gravity) && unknown parameter 'acceleraton' && did you mean 'acceleration'
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.domain(lo=(0, 0, 0), hi=(0.1, 0.1, 0.1))
sim.kernel_radius(0.02)
sim.timestep(0.001)
sim.lattice(lo=(0.02, 0.02, 0.02), hi=(0.06, 0.06, 0.06), spacing=0.01)  # 64 particles
sim.fix("gravity", "gravity")
sim.fix("pbf", "pbf")
sim.fix("walls", "box")
sim.fix("g2", "gravity", acceleraton=(0, 0, -9.81))
