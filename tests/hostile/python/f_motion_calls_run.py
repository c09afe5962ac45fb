# a motion function that calls run()
# Expected: refused, Error: 'ball' && run cannot be called during a run
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.domain(lo=(0, 0, 0), hi=(0.1, 0.1, 0.1))
sim.kernel_radius(0.02)
sim.timestep(0.001)
sim.lattice(lo=(0.02, 0.02, 0.02), hi=(0.06, 0.06, 0.06), spacing=0.01)  # 64 particles
sim.fix("gravity", "gravity")
sim.fix("pbf", "pbf")
sim.fix("walls", "box")
def motion(t):
    sim.run(1)
sim.fix("ball", "solid", shape="sphere", center=(0.06, 0.06, 0.06), radius=0.02, motion=motion)
sim.run(2)
