# Simulation(log_level='loud')
# Expected: refused, Error: log_level && loud
import pbfengine
pbfengine.Simulation(log=None, log_level="loud")
