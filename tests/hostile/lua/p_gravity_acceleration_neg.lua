-- fix/compute gravity: acceleration = {-1, -1, -1}: accepted ({0,0,0} (no gravity) and {-1,-1,-1} are legal; 1e300 m/s^2 moves a particle across the domain in one step)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {acceleration = {-1, -1, -1}})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.run(2)
