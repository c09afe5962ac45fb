-- dfsph at a step of 0.5 s: the first step's velocity would carry particles past their kernel; refused at step 1 naming the CFL bound
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.5)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("dfsph", "dfsph", {})
pbf.fix("walls", "box", {})
pbf.run(3)
