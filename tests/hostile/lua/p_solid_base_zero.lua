-- fix/compute solid: base = {0, 0, 0}: accepted (a cylinder's base: 0 and -1 give a pillar along the diagonal through the fluid (the particles in it are left out), legal; 1e300 is beyond any scene)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("ball", "solid", {shape = "cylinder", top = {0.08, 0.08, 0.08}, radius = 0.01, base = {0, 0, 0}})
pbf.run(2)
