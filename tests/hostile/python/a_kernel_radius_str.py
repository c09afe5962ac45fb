# kernel_radius('0.02')
# Expected: refused, TypeError: kernel_radius
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.kernel_radius("0.02")
