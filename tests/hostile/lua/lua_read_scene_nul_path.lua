-- a path with a NUL byte: refused (no file has that name)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.read_scene("s.txt\0.lua")
