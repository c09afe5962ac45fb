-- a probe defined inside a solid whose map a run has built
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("block", "solid", {shape = "box", lo = {0.06, -1, -1}, hi = {1, 1, 1}})
pbf.run(1)
pbf.compute("p", "probe", {points = {{0.09, 0.03, 0.02}}, field = "density"})
print(pbf.value("p"))
