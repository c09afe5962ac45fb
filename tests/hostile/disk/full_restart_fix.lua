-- a periodic restart larger than the file size limit
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.03, 0.03, 0.03}, hi = {0.05, 0.05, 0.05}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("restarts", "restart", {path = "out/r.*.restart", every = 1, keep = 5})
pbf.run(2)
pbf.lattice{lo = {0.0, 0.0, 0.06}, hi = {0.1, 0.1, 0.1}, spacing = 0.01}
pbf.run(2)
