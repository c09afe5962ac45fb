-- vtk_collection into blocker: refused, naming the path
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.03, 0.03, 0.03}, hi = {0.05, 0.05, 0.05}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("frames", "dump/vtk", {path = "out/f_*.vtu", every = 1, collection = "blocker/c.pvd"})
pbf.run(1)
