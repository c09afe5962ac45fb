-- fix/compute cfl: max_dt = 1e300: accepted (0 is the script's dt; 1e300 s is only a bound the CFL rule undercuts)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.0002)
pbf.lattice{lo = {0, 0, 0}, hi = {0.04, 0.04, 0.04}, spacing = 0.01}
pbf.fix("integrator", "leapfrog", {})
pbf.fix("gravity", "gravity", {})
pbf.fix("wcsph", "wcsph", {})
pbf.fix("viscosity", "sph_viscosity", {})
pbf.fix("walls", "box", {})
pbf.fix("cfl", "cfl", {max_dt = 1e300})
pbf.run(2)
