# a motion function that returns NaN from t = 1.5 ms
# Expected: refused, Error: 'ball' && t = 0.002 && nan && f_motion_nan_later.py:12
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
    return {"translate": (0, 0, 0) if t < 0.0015 else (float("nan"), 0, 0)}
sim.fix("ball", "solid", shape="sphere", center=(0.06, 0.06, 0.06), radius=0.02, motion=motion)
sim.run(3)
