-- a dfsph beside a leapfrog: refused (both integrate time)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.0002)
pbf.lattice{lo = {0, 0, 0}, hi = {0.04, 0.04, 0.04}, spacing = 0.01}
pbf.fix("integrator", "leapfrog", {})
pbf.fix("dfsph", "dfsph", {})
pbf.run(1)
