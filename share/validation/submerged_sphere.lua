-- submerged_sphere.lua: the fluid's force on a sphere held under water, against Archimedes'
-- rho0 V g, at a chosen spacing (share/validation/submerged_sphere.sh runs it at two). A tank
-- 0.3 x 0.3 m of water 0.15 m deep (PBF, XSPH), a sphere of radius 0.04 m centred 0.075 m up,
-- held all run long (a body with a hold longer than the run: its load is the fluid's force).
-- Prints "buoyancy RATIO": the force's mean over the last 0.3 s of 1.5 s over rho0 V g.
--
--   pbfengine run share/validation/submerged_sphere.lua -v s=0.01
local s = var.s or 0.01
local g, r = 9.81, 0.04
pbf.domain{lo = {0, 0, 0}, hi = {0.3, 0.3, 0.3}}
pbf.kernel_radius(2 * s)
pbf.timestep(0.4 * 2 * s / math.sqrt(2 * g * 0.1))
pbf.lattice{lo = {0, 0, 0}, hi = {0.3, 0.3, 0.15}, spacing = s}
pbf.fix("gravity", "gravity", {acceleration = {0, 0, -g}})
pbf.fix("pbf", "pbf", {})
pbf.fix("xsph", "xsph", {})
pbf.fix("walls", "box", {})
pbf.fix("ball", "solid", {shape = "sphere", center = {0.15, 0.15, 0.075}, radius = r, density = 2000, hold = 100})
pbf.compute("b", "body", {solid = "ball"})
pbf.run_until(1.2)
local sum, n = 0, 0
while pbf.time() < 1.5 - 1e-9 do
  pbf.run(1)
  sum, n = sum + pbf.value("b").fz, n + 1
end
print(string.format("buoyancy %.4f (radius %.3g spacings)", sum / n / (1000 * 4 / 3 * math.pi * r ^ 3 * g), r / s))
