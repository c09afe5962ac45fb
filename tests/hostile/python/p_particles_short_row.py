# read_particles of a CSV whose row 2 has two fields
# Expected: refused, Error: p.csv:2:
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.domain(lo=(0, 0, 0), hi=(0.1, 0.1, 0.1))
sim.kernel_radius(0.02)
sim.timestep(0.001)
open("p.csv", "w").write("x,y,z\n0.01,0.02\n")
sim.read_particles("p.csv")
