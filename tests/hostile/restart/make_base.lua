-- make_base.lua: the base restart the replay derives its damaged restarts from, written by the binary
-- under test: 8 particles after 2 steps, with a dump's saved state.
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.03, 0.03, 0.03}, hi = {0.05, 0.05, 0.05}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("frames", "dump/text", {path = "out/f_*.txt", every = 1})
pbf.run(2)
pbf.write_restart(var.out or "base.restart")
