-- h = 1 m = 100 spacings: refused
pbf.domain{lo = {0, 0, 0}, hi = {2, 2, 2}}
pbf.kernel_radius(1)
pbf.timestep(0.001)
pbf.lattice{lo = {0.9, 0.9, 0.9}, hi = {0.94, 0.94, 0.94}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.run(1)
