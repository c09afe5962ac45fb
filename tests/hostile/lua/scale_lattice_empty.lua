-- spacing 0.05 in a region 0.04 wide (h = 0.1): no particle, refused
pbf.domain{lo = {0, 0, 0}, hi = {1, 1, 1}}
pbf.kernel_radius(0.1)
pbf.timestep(0.001)
pbf.lattice{lo = {0.5, 0.5, 0.5}, hi = {0.54, 0.54, 0.54}, spacing = 0.05}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.run(1)
