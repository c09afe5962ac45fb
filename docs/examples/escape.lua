-- escape.lua: water without walls falls out of the domain (docs/scripting.md, "Run errors")
pbf.domain{lo = {0, 0, 0}, hi = {0.2, 0.2, 0.4}}
pbf.kernel_radius(0.02)
pbf.timestep(0.002)
pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.2}, spacing = 0.01}
pbf.fix("gravity", "gravity", {}) pbf.fix("pbf", "pbf", {})   -- and no box fix
if var.every then pbf.fix("restarts", "restart", {path = "escape.*.restart", every = var.every}) end
pbf.run(100)
