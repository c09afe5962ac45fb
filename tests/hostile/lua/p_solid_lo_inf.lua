-- fix/compute solid: lo = {1/0, 1/0, 1/0}: refused (a box's lower corner: 0 and -1 give a box from there to hi (partly outside the domain, the fluid's lowest layer left out), legal; 1e300 exceeds hi and any scene)
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("ball", "solid", {shape = "box", hi = {0.095, 0.095, 0.03}, lo = {1/0, 1/0, 1/0}})
pbf.run(2)
