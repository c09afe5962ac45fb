# lua('os.exit(3)'): refused, so Python unwinds (finally blocks run)
# Expected: refused, Error: os.exit(3) && cannot end the process
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
try:
    sim.lua("os.exit(3)")
finally:
    print("unwound")
