-- fix/compute damping: to = {1e300, 1e300, 1e300}: refused (where it is full, any point other than 'from' up to 1e6 m away ({0,0,0}, {-1,-1,-1}: a zone growing toward -x, legal); 1e300 is beyond any scene)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("zone", "damping", {from = {0.05, 0, 0}, to = {1e300, 1e300, 1e300}})
pbf.run(2)
