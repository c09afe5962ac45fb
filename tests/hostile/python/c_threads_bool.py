# Simulation(threads=True)
# Expected: refused, TypeError: threads || Error: threads && bool
import pbfengine
pbfengine.Simulation(threads=True, log=None, log_level="warn")
