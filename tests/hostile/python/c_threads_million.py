# Simulation(threads=10**6)
# Expected: refused, Error: Simulation && threads && 1000000
import pbfengine
pbfengine.Simulation(threads=10**6, log=None)
