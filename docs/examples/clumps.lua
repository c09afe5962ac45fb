-- clumps.lua: WCSPH at 30 times its stable time step, with the density stop of wcsph turned
-- off, collapses into clumps (docs/scripting.md, "Run errors")
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.3}}
pbf.kernel_radius(0.02)
pbf.timestep(0.004)
pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.2}, spacing = 0.01}
pbf.fix("integrator", "leapfrog", {}) pbf.fix("gravity", "gravity", {}) pbf.fix("walls", "box", {})
pbf.fix("wcsph", "wcsph", {max_density_error = 1e300}) pbf.fix("viscosity", "sph_viscosity", {})
pbf.run(1000)
