-- a domain from -1e308 to 1e308 m (its size overflows): refused
pbf.domain{lo = {-1e308, -1e308, -1e308}, hi = {1e308, 1e308, 1e308}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.run(1)
