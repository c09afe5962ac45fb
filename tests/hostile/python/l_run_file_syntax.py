# run_file of a script with a syntax error on line 2
# Expected: refused, Error: syn.lua:2:
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
open("syn.lua", "w").write("pbf.domain{lo = {0, 0, 0}, hi = {1, 1, 1}\npbf.run(1)\n")
sim.run_file("syn.lua")
