-- axes.lua: the periodic axes of a scene given as one -v word, "xy" -> {"x", "y"}, for
-- pbf.domain's `periodic` (which names a wrong letter itself).
--   local axes = require("axes")
--   pbf.domain{lo = ..., hi = ..., periodic = axes(var.periodic)}
return function(word)
  local names = {}
  for letter in tostring(word or ""):gmatch(".") do names[#names + 1] = letter end
  return names
end
