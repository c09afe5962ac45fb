-- scene_error.lua: an error inside the function pbf.scene calls names the line inside it.
pbf.scene(function()
  pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
  pbf.kernel_radius(-1)
end)
