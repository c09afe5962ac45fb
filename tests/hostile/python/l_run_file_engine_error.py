# run_file of a script whose line 1 the engine refuses
# Expected: refused, Error: e.lua:1: && kernel radius
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
open("e.lua", "w").write("pbf.kernel_radius(-1)\n")
sim.run_file("e.lua")
