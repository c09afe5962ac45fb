# run_file of a missing file
# Expected: refused, Error: nope.lua
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.run_file("nope.lua")
