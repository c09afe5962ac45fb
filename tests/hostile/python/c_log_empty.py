# Simulation(log=''): an empty log path
# Expected: refused, Error: log && None
import pbfengine
pbfengine.Simulation(log="")
