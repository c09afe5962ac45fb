-- fix/compute outflow: point = {0/0, 0/0, 0/0}: refused (any point up to 1e6 m away: {0,0,0} and {-1,-1,-1} put every particle beyond the plane, which drains the scene at the first step and the run goes on empty, legal; 1e300 is beyond any scene)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("drain", "outflow", {region = "half_space", normal = {1, 0, 0}, point = {0/0, 0/0, 0/0}})
pbf.run(2)
