-- an emitter with velocity = function(t, x, y, z) return {0, 0, t > 0.002 and 0/0 or -1} end: refused
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("jet", "emitter", {center = {0.08, 0.05, 0.08}, normal = {0, 0, -1}, size = {0.02, 0.02}, velocity = function(t, x, y, z) return {0, 0, t > 0.002 and 0/0 or -1} end})
pbf.run(3)
