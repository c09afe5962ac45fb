# Ctrl-C during lua('while true do end')
# Expected: refused, KeyboardInterrupt || Interrupted || Error: interrupted
import os
import subprocess
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
subprocess.Popen(["/bin/sh", "-c", "sleep 1; kill -INT %d" % os.getpid()], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
sim.lua("while true do end")
