-- fix/compute solid: point = {1/0, 1/0, 1/0}: refused (a plane through the origin with normal +z is the floor of the domain (legal); at z = -1 the solid z < -1 lies entirely outside the domain; 1e300 is beyond any scene)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("ball", "solid", {shape = "plane", normal = {0, 0, 1}, point = {1/0, 1/0, 1/0}})
pbf.run(2)
