pbf.every("stop", 4, function(step)
  error("stop at step " .. step)
end)
pbf.kernel_radius(0.2)
pbf.timestep(0.01)
pbf.lattice{lo = {0, 0, 0}, hi = {0.5, 0.5, 0.5}, spacing = 0.1}
pbf.run(10)
