-- clumps.lua: PBF with a two-sided constraint, no wall density and the paper's Jacobi
-- relaxation 1, an unstable setting (tension pulls particles together, and the iteration
-- overshoots), collapses into clumps (docs/scripting.md, "Run errors")
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.3}}
pbf.kernel_radius(0.02)
pbf.timestep(0.004)
pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.2}, spacing = 0.01}
pbf.fix("gravity", "gravity", {}) pbf.fix("walls", "box", {wall_density = false})
pbf.fix("pbf", "pbf", {one_sided = false, relaxation = 1})
pbf.run(1000)
