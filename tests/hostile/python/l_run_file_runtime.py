# run_file of a script indexing nil on line 2
# Expected: refused, Error: rt.lua:2: && nil
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
open("rt.lua", "w").write("local x = nil\nprint(x.y)\n")
sim.run_file("rt.lua")
