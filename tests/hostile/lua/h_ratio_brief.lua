-- a lattice of spacing 0.001 with h = 2: 2000 spacings, refused
pbf.domain{lo = {0, 0, 0}, hi = {4, 4, 4}}
pbf.kernel_radius(2)
pbf.timestep(0.001)
pbf.lattice{lo = {1, 1, 1}, hi = {1.004, 1.004, 1.004}, spacing = 0.001}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.run(1)
