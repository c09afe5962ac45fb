-- fix/compute vorticity: epsilon = 1e300: refused (0 is no confinement; a negative one damps the wrong way; 1e300 turns round-off vorticity into accelerations no step survives)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("vorticity", "vorticity", {epsilon = 1e300})
pbf.run(2)
