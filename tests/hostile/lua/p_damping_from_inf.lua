-- fix/compute damping: from = {1/0, 1/0, 1/0}: refused (the zone's start, any point up to 1e6 m away ({0,0,0} and {-1,-1,-1} start it before the fluid, legal); 1e300 is beyond any scene)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("zone", "damping", {to = {0.1, 0, 0}, from = {1/0, 1/0, 1/0}})
pbf.run(2)
