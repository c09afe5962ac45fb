-- dfsph with min_iterations above max_iterations: refused, naming both
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("dfsph", "dfsph", {min_iterations = 5, max_iterations = 3})
pbf.run(1)
