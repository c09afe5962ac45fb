-- probe_column.lua: the column of "Pressure in PBF" (docs/physics.md): water 0.1 m deep on a
-- 0.08 m square floor at 1 cm spacing, probes every centimetre up its axis, from the floor.
-- Prints each probe's pressure averaged over t = settle to t_end against rho0 g depth, the
-- depth below the 99.5th percentile of z plus half a spacing (averaged likewise).
--
--   pbfengine run docs/examples/probe_column.lua [-v solver=wcsph] [-v density=continuity]
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
package.path = here .. "../../share/lua/?.lua;" .. package.path
local s, H, W, g = 0.01, 0.1, 0.08, 9.81
local wcsph = var.solver == "wcsph"
local settle, t_end = var.settle or (wcsph and 0.4 or 0.6), var.t_end or (wcsph and 0.7 or 1.0)
pbf.domain{lo = {0, 0, 0}, hi = {W, W, 1.5 * H}}
pbf.kernel_radius(2 * s)
pbf.timestep(0.4 * 2 * s / math.sqrt(2 * g * H))
pbf.lattice{lo = {0, 0, 0}, hi = {W, W, H}, spacing = s}
pbf.fix("gravity", "gravity", {})
if wcsph then
  require("solvers").wcsph{density = var.density}
else
  pbf.fix("pbf", "pbf", {})
  pbf.fix("xsph", "xsph", {c = 0.01})
end
pbf.fix("walls", "box", {})
local points, labels = {}, {}
for k = 0, 8 do points[#points + 1], labels[#labels + 1] = {W / 2, W / 2, k * s}, "z" .. k end
pbf.compute("p", "probe", {points = points, labels = labels})
pbf.compute("top", "front", {axis = "z", percentile = 99.5})
pbf.run_until(settle)
local sum, top, samples = {}, 0, 0
for k = 0, 8 do sum[k] = 0 end
pbf.every("average", 1, function()
  local p = pbf.value("p")
  for k = 0, 8 do sum[k] = sum[k] + p["z" .. k] end
  top, samples = top + pbf.value("top"), samples + 1
end)
pbf.run_until(t_end)
local surface = top / samples + s / 2
local line = string.format("surface %.4f m; probe height 0..8 cm against rho0 g depth:", surface)
for k = 0, 8 do
  local expected = 1000 * g * (surface - k * s)
  line = line .. string.format(" %+.1f%%", 100 * (sum[k] / samples / expected - 1))
end
print(line)
