# lua() of unfinished text
# Expected: refused, Error: lua:1:
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.lua("pbf.run(")
