-- pbf.read_scene of a link r.txt -> /dev/urandom: refused, no hang
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.read_scene("r.txt")
