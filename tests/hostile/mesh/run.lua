-- run.lua: a mesh file (-v file=PATH), in the coordinates of the unit cube [0, 1]^3, used as
--   -v use=container  the solid fix with fluid = "inside", scaled to [0.01, 0.09]^3 around the fluid;
--   -v use=obstacle   the solid fix (fluid outside), scaled to 0.03 m in the corner x, y > 0.065 beside
--                     the fluid;
--   -v use=lattice    pbf.lattice{mesh = PATH}, scaled to [0.02, 0.06]^3: 64 particles.
-- -v orient=true or false, when given, is the `orient` of the solid fix and of pbf.lattice.
-- The domain is [0, 0.1]^3, h = 0.02 m, the lattice spacing 0.01 m; then two steps.
local orient = nil
if var.orient ~= nil then orient = var.orient == "true" end
pbf.domain{lo = {0, 0, 0}, hi = {0.1, 0.1, 0.1}}
pbf.kernel_radius(0.02)
pbf.timestep(0.001)
if var.use == "lattice" then
  pbf.lattice{mesh = var.file, scale = 0.04, translate = {0.02, 0.02, 0.02}, spacing = 0.01, orient = orient}
else
  pbf.lattice{lo = {0.02, 0.02, 0.02}, hi = {0.06, 0.06, 0.06}, spacing = 0.01}
end
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
if var.use == "container" then
  pbf.fix("tank", "solid", {file = var.file, fluid = "inside", scale = 0.08, translate = {0.01, 0.01, 0.01},
                            orient = orient})
elseif var.use == "obstacle" then
  pbf.fix("block", "solid", {file = var.file, scale = 0.03, translate = {0.065, 0.065, 0.01},
                             orient = orient})
elseif var.use ~= "lattice" then
  error("-v use=container, obstacle or lattice")
end
pbf.run(2)
