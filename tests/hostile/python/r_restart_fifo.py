# read_restart of a FIFO
# Expected: refused, Error: p.restart && not a regular file
import os
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
os.mkfifo("p.restart")
sim.read_restart("p.restart")
