# run_file('')
# Expected: refused, Error: run_file && empty
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.run_file("")
