-- a lattice of 1e12 particles needs more memory than any machine: refused, naming the memory
pbf.domain{lo = {0, 0, 0}, hi = {10, 10, 10}}
pbf.kernel_radius(0.002)
pbf.timestep(0.001)
pbf.lattice{lo = {0, 0, 0}, hi = {10, 10, 10}, spacing = 0.001}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.run(1)
