-- too_large.lua: half the usual spacing at a step that keeps the column 7% compressed.
pbf.domain{lo = {0, 0, 0}, hi = {0.4, 0.1, 0.4}}
pbf.kernel_radius(0.01)
pbf.timestep(0.003)
pbf.lattice{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.2}, spacing = 0.005}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {iterations = 2})
pbf.fix("walls", "box", {})
pbf.run(70)
