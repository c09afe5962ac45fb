-- fix/compute wcsph: gravity = 1e300: refused (the magnitude g of the default c0 = 10 sqrt(2 |g| H): 0 gives c0 = 0 (no pressure); -1 is legal (a downward g, as the gravity fix writes it); 1e300 gives a c0 whose square overflows)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.0002)
pbf.lattice{lo = {0, 0, 0}, hi = {0.04, 0.04, 0.04}, spacing = 0.01}
pbf.fix("integrator", "leapfrog", {})
pbf.fix("gravity", "gravity", {})
pbf.fix("wcsph", "wcsph", {gravity = 1e300})
pbf.fix("viscosity", "sph_viscosity", {})
pbf.fix("walls", "box", {})
pbf.fix("cfl", "cfl", {})
pbf.run(2)
