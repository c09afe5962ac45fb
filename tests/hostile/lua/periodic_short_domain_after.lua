-- h = 0.02 m, then a period of 0.03 m along y: refused at pbf.domain
pbf.kernel_radius(0.02)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.03, 0.1}, periodic = {"y"}}
