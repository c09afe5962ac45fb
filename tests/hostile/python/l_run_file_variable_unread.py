# run_file with a variable the script never reads
# Expected: warned, 'm'
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
open("v.lua", "w").write("print(1)\n")
sim.run_file("v.lua", m=3)
