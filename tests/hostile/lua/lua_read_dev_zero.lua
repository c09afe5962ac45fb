-- pbf.read_scene("/dev/zero"): refused at once (not a regular file), no hang
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.read_scene("/dev/zero")
