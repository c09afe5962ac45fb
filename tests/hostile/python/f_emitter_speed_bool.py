# an emitter speed function returning True
# Expected: refused, Error: 'jet' && 'speed' && bool
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.domain(lo=(0, 0, 0), hi=(0.1, 0.1, 0.1))
sim.kernel_radius(0.02)
sim.timestep(0.001)
sim.lattice(lo=(0.02, 0.02, 0.02), hi=(0.06, 0.06, 0.06), spacing=0.01)  # 64 particles
sim.fix("gravity", "gravity")
sim.fix("pbf", "pbf")
sim.fix("walls", "box")
def speed(t, x, y, z):
    return True
sim.fix("jet", "emitter", center=(0.08, 0.05, 0.08), normal=(0, 0, -1), size=(0.02, 0.02), speed=speed)
sim.run(3)
