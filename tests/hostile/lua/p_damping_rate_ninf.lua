-- fix/compute damping: rate = -1/0: refused (a relaxation rate in (0, 1e6] per second: 0 damps nothing, a negative one accelerates, 1e300 is no rate)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("zone", "damping", {from = {0.05, 0, 0}, to = {0.1, 0, 0}, rate = -1/0})
pbf.run(2)
