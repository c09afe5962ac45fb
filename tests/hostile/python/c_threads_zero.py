# Simulation(threads=0)
# Expected: refused, Error: Simulation && threads
import pbfengine
pbfengine.Simulation(threads=0, log=None)
