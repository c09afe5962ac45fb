-- a dump/text frame larger than the file size limit
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.03, 0.03, 0.03}, hi = {0.05, 0.05, 0.05}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.run(1)
pbf.write_restart("last.restart")
pbf.lattice{lo = {0.0, 0.0, 0.06}, hi = {0.1, 0.1, 0.1}, spacing = 0.01}
pbf.fix("frames", "dump/text", {path = "out/f_*.txt", every = 1, fields = {"position", "velocity", "mass", "id"}})
pbf.run(2)
