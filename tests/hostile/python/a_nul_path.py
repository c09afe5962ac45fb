# read_restart of a path with a NUL byte
# Expected: refused, Error: zero byte || ValueError: null byte || Error: b.restart
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.read_restart("a\x00b.restart")
