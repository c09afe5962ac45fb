-- fix/compute solid: top = {-1, -1, -1}: accepted (a cylinder's top: 0 gives a pillar lying on the floor, -1 one leaving the domain through it, both legal; 1e300 is beyond any scene)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("ball", "solid", {shape = "cylinder", base = {0.08, 0.08, 0.02}, radius = 0.01, top = {-1, -1, -1}})
pbf.run(2)
