-- a period of 0.1 m, then h = 0.06 m (2 h = 0.12 m): refused at pbf.kernel_radius
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}, periodic = {"x", "y"}}
pbf.kernel_radius(0.06)
