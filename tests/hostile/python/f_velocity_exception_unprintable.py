# a lattice velocity function raising an exception whose str() fails
# Expected: refused, Error: lattice && velocity function
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
sim.domain(lo=(0, 0, 0), hi=(0.1, 0.1, 0.1))
sim.kernel_radius(0.02)
sim.timestep(0.001)
class Unprintable(Exception):
    def __str__(self):
        raise RuntimeError("no str")
def velocity(x, y, z):
    raise Unprintable()
sim.lattice(lo=(0.02, 0.02, 0.02), hi=(0.06, 0.06, 0.06), spacing=0.01, velocity=velocity)
