# run_file with a variable that is None
# Expected: refused, Error: 'n' || TypeError: 'n'
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
open("v.lua", "w").write("print(var.n)\n")
sim.run_file("v.lua", n=None)
