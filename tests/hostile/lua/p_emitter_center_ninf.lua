-- fix/compute emitter: center = {-1/0, -1/0, -1/0}: refused (the opening must lie in the domain and face into it: at the corner {0,0,0} its first layer would leave the domain, {-1,-1,-1} is outside it)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("jet", "emitter", {normal = {0, 0, -1}, size = {0.02, 0.02}, speed = 0.5, center = {-1/0, -1/0, -1/0}})
pbf.run(2)
