# Ctrl-C from outside during a long run
# Expected: refused, Interrupted: interrupted (Ctrl-C) && restart
import os
import subprocess
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.domain(lo=(0, 0, 0), hi=(0.1, 0.1, 0.1))
sim.kernel_radius(0.02)
sim.timestep(0.001)
sim.lattice(lo=(0.02, 0.02, 0.02), hi=(0.06, 0.06, 0.06), spacing=0.01)  # 64 particles
sim.fix("gravity", "gravity")
sim.fix("pbf", "pbf")
sim.fix("walls", "box")
subprocess.Popen(["/bin/sh", "-c", "sleep 1; kill -INT %d" % os.getpid()], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
sim.thermo(every=0)
sim.run(10**8)
