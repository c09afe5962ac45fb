# a list of names with a number in it
# Expected: refused, Error: domain && 'periodic' && entry 2
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.domain(lo=(0, 0, 0), hi=(0.1, 0.1, 0.1), periodic=["x", 1])
