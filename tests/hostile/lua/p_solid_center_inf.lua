-- fix/compute solid: center = {1/0, 1/0, 1/0}: refused (the origin puts the sphere on the domain's corner (an eighth of it inside, 0.02 m deep: legal); -1 puts it entirely outside the domain; 1e300 is beyond any scene)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("ball", "solid", {shape = "sphere", radius = 0.02, center = {1/0, 1/0, 1/0}})
pbf.run(2)
