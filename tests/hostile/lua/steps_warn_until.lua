-- dt = 1e-9 s to t = 0.05 s: 5e7 steps, warned; the callback stops it at step 1
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.timestep(1e-9)
pbf.every("stop", 1, function(step) error("stopped at step " .. step) end)
pbf.run_until(0.05)
