-- free_cube.lua: a cube of 10^3 particles at rest density, at rest, in zero gravity and far
-- from any wall. It is in equilibrium, so nothing should move. Prints the largest speed and
-- the cube's width after 2 s for the pbf parameters given (share/validate_hydrostatic.sh
-- compares artificial-pressure strengths with it).
--
--   pbfengine run share/validation/free_cube.lua [-v scorr_k=K] [-v one_sided=false]
local function flag(value, default)
  if value == nil then return default end
  return not (value == false or value == 0 or value == "false")
end
pbf.domain{lo = {0, 0, 0}, hi = {1, 1, 1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.002)
pbf.lattice{lo = {0.45, 0.45, 0.45}, hi = {0.55, 0.55, 0.55}, spacing = 0.01}
pbf.fix("pbf", "pbf", {scorr_k = var.scorr_k, one_sided = flag(var.one_sided, true)})
pbf.compute("box", "extent")
pbf.compute("v", "speed")
local ok, message = pcall(pbf.run, 1000)
local box = pbf.value("box")
print(string.format("free_cube: max speed %.3g m/s, width %.4g m (from 0.09 m)%s", pbf.value("v").max,
                    box.xmax - box.xmin, ok and "" or ", stopped: a particle left the 1 m box"))
