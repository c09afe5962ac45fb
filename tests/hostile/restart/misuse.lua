-- misuse.lua: pbf.read_restart called wrongly (-v how=...).
pbf.kernel_radius(0.02)
if var.how == "after_particles" then
  pbf.lattice{lo = {0.03, 0.03, 0.03}, hi = {0.05, 0.05, 0.05}, spacing = 0.01}
end
pbf.read_restart(var.file)
if var.how == "twice" then pbf.read_restart(var.file) end
pbf.run(0)
