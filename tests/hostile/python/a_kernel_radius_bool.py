# kernel_radius(True)
# Expected: refused, TypeError: kernel_radius || Error: kernel && bool
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.kernel_radius(True)
