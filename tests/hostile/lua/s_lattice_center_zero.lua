-- pbf.lattice: {0, 0, 0}: accepted (the origin keeps the corner sites; {-1,-1,-1} and 1e300 keep no particle: a lattice that creates none is refused)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0, 0, 0}, hi = {0.04, 0.04, 0.04}, spacing = 0.01, center = {0, 0, 0}, radius = 0.03}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.run(2)
