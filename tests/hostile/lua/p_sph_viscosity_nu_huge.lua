-- fix/compute sph_viscosity: nu = 1e300: refused (0 is an inviscid fluid; 1e300 m^2/s is no fluid)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.0002)
pbf.lattice{lo = {0, 0, 0}, hi = {0.04, 0.04, 0.04}, spacing = 0.01}
pbf.fix("integrator", "leapfrog", {})
pbf.fix("gravity", "gravity", {})
pbf.fix("wcsph", "wcsph", {})
pbf.fix("viscosity", "sph_viscosity", {kind = "laplacian", nu = 1e300})
pbf.fix("walls", "box", {})
pbf.fix("cfl", "cfl", {})
pbf.run(2)
