-- fix/compute pbf: epsilon = -1/0: refused (the relaxation must be positive (0 divides 0 by 0 for an isolated particle); 1e300 S0 is legal, it only weakens the constraint to nothing)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {epsilon = -1/0})
pbf.fix("walls", "box", {})
pbf.run(2)
