# Ctrl-C during a run (sent from a callback, which then returns)
# Expected: refused, Interrupted: interrupted (Ctrl-C) && after step 2 && restart
import os
import signal
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.domain(lo=(0, 0, 0), hi=(0.1, 0.1, 0.1))
sim.kernel_radius(0.02)
sim.timestep(0.001)
sim.lattice(lo=(0.02, 0.02, 0.02), hi=(0.06, 0.06, 0.06), spacing=0.01)  # 64 particles
sim.fix("gravity", "gravity")
sim.fix("pbf", "pbf")
sim.fix("walls", "box")
def watch(step, time):
    if step == 2:
        os.kill(os.getpid(), signal.SIGINT)
sim.every("watch", 1, watch)
sim.run(100)
