-- fix/compute dump/movie: center = {-1, -1, -1}: accepted (as dump/image)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("movie", "dump/movie", {path = "out/m.mp4", every = 1, width = 32, height = 24, center = {-1, -1, -1}})
pbf.run(2)
