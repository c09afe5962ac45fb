-- fix/compute cfl: sound_speed = -1: refused (0 is wcsph's c0; 1e300 m/s gives steps of 3e-303 s)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.0002)
pbf.lattice{lo = {0, 0, 0}, hi = {0.04, 0.04, 0.04}, spacing = 0.01}
pbf.fix("integrator", "leapfrog", {})
pbf.fix("gravity", "gravity", {})
pbf.fix("wcsph", "wcsph", {})
pbf.fix("viscosity", "sph_viscosity", {})
pbf.fix("walls", "box", {})
pbf.fix("cfl", "cfl", {sound_speed = -1})
pbf.run(2)
