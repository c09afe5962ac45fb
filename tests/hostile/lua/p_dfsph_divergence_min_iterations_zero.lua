-- fix/compute dfsph: divergence_min_iterations = 0: refused (a count in 1..10000)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("dfsph", "dfsph", {divergence_min_iterations = 0})
pbf.fix("walls", "box", {})
pbf.run(2)
