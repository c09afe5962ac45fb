# read_restart of a restart cut in half
# Expected: refused, Error: t.restart && truncated
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.domain(lo=(0, 0, 0), hi=(0.1, 0.1, 0.1))
sim.kernel_radius(0.02)
sim.timestep(0.001)
sim.lattice(lo=(0.02, 0.02, 0.02), hi=(0.06, 0.06, 0.06), spacing=0.01)  # 64 particles
sim.fix("gravity", "gravity")
sim.fix("pbf", "pbf")
sim.fix("walls", "box")
sim.write_restart("r.restart")
data = open("r.restart", "rb").read()
open("t.restart", "wb").write(data[:len(data) // 2])
pbfengine.Simulation(log=None, log_level="warn").read_restart("t.restart")
