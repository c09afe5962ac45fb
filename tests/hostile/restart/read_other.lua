-- read_other.lua: reads a restart into a pipeline that differs from the saved one (-v change=...).
pbf.read_restart(var.file)
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
if var.change ~= "no_walls" then pbf.fix("walls", "box", {}) end
if var.change == "extra_xsph" then pbf.fix("xsph", "xsph", {}) end
if var.change == "frames_vtk" then
  pbf.fix("frames", "dump/vtk", {path = "out/f_*.vtu", every = 1})
else
  pbf.fix("frames", "dump/text", {path = "out/f_*.txt", every = 1})
end
pbf.run(1)
