# read_scene of a header that ends on line 2
# Expected: refused, Error: sc.txt:2:
import pbfengine
sim = pbfengine.Simulation(log=None, log_level="warn")
open("sc.txt", "w").write("3\n0.001 0.02\n")
sim.read_scene("sc.txt")
