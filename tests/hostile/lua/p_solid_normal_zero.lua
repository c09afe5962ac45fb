-- fix/compute solid: normal = {0, 0, 0}: refused (a direction: {0,0,0} has none; {-1,-1,-1} puts the solid above the plane x+y+z = 0.11 (part of the fluid left out), legal; its range is [-1e6, 1e6], so 1e300 is refused)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("ball", "solid", {shape = "plane", point = {0.05, 0.05, 0.01}, normal = {0, 0, 0}})
pbf.run(2)
