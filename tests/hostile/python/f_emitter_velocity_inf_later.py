# an emitter velocity function that returns infinity from t = 1.5 ms
# Expected: refused, Error: 'jet' && 'velocity' && t = 0.0015 && finite && f_emitter_velocity_inf_later.py:12
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.domain(lo=(0, 0, 0), hi=(0.1, 0.1, 0.1))
sim.kernel_radius(0.02)
sim.timestep(0.001)
sim.lattice(lo=(0.02, 0.02, 0.02), hi=(0.06, 0.06, 0.06), spacing=0.01)  # 64 particles
sim.fix("gravity", "gravity")
sim.fix("pbf", "pbf")
sim.fix("walls", "box")
def velocity(t, x, y, z):
    return (0, 0, -1) if t < 0.0015 else (0, 0, float("inf"))
sim.fix("jet", "emitter", center=(0.08, 0.05, 0.08), normal=(0, 0, -1), size=(0.02, 0.02), velocity=velocity)
sim.run(4)
