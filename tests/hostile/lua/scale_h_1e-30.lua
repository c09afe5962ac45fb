-- h = 1e-30 m in a 1 m domain: refused
pbf.domain{lo = {0, 0, 0}, hi = {1, 1, 1}}
pbf.kernel_radius(1e-30)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.run(1)
