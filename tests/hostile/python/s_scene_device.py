# read_scene of /dev/zero
# Expected: refused, Error: /dev/zero && not a regular file
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.read_scene("/dev/zero")
