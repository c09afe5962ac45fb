-- run.lua: reads a particle file (-v file=PATH) into the domain [0, 0.1]^3 with h = 0.02 and runs
-- two PBF steps.
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.read_particles(var.file)
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.run(2)
