# read_restart of a missing file
# Expected: refused, Error: nope.restart && no such file
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.read_restart("nope.restart")
