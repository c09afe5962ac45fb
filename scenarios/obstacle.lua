-- obstacle.lua: a dam break against an obstacle read from a mesh file. A water column 0.3 m
-- wide, 0.5 m high and as deep as the tank is released against the wall x = 0 of a tank
-- 1.2 m long; the surge meets a ramp (scenarios/geometry/wedge.stl, a binary STL, scaled to
-- 0.24 m long, 0.3 m high and 0.2 m wide, its slope facing the flow) in the middle of the
-- floor, is thrown up its slope and flows around its sides, and splashes against the far
-- wall. The tank's walls are
-- the analytic box; the ramp is a `solid` (docs/user-guide.md#solids).
--
--   pbfengine run scenarios/obstacle.lua [-v particles=20000] [-v t_end=1.0] [-v out=out]
--   pbfengine run scenarios/obstacle.lua -v images=0.05      (pictures, out/image_*.png)
--   pbfengine run scenarios/obstacle.lua -v vtk=0.02          (ParaView: out/vtk/frame.pvd)
--
-- Variables: particles (about how many, default 20000), t_end (simulated seconds, default
-- 1.0), out (output directory, default "out"), friction (the ramp's wall friction rate in
-- 1/s, default 0: free slip), solver ("pbf", the default, or "wcsph"); images, movie and vtk
-- as in every scenario (share/lua/outputs.lua).
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
package.path = here .. "../share/lua/?.lua;" .. package.path
local N = var.particles or 20000
local t_end = var.t_end or 1.0
local out = var.out or "out"
local g = 9.81
local L, W, H = 1.2, 0.4, 0.6          -- the tank
local a, b = 0.3, 0.5                  -- the column: a long, b high, the tank's width deep

local s = (a * W * b / N) ^ (1 / 3)    -- lattice spacing
s = W / math.floor(W / s + 0.5)        -- a whole number of layers across the tank
local h = 2 * s
local dt = var.dt or 0.4 * h / math.sqrt(2 * g * b)   -- 0.4 h per step at the free-fall speed

pbf.domain{lo = {0, 0, 0}, hi = {L, W, H}}
pbf.kernel_radius(h)
pbf.timestep(dt)
local n = pbf.lattice{lo = {0, 0, 0}, hi = {a, W, b}, spacing = s}
print(string.format("obstacle: %d particles, spacing %.4g m, h %.4g m, dt %.3g s", n, s, h, dt))

pbf.fix("gravity", "gravity", {acceleration = {0, 0, -g}})
if (var.solver or "pbf") == "wcsph" then
  require("solvers").wcsph{}
else
  pbf.fix("pbf", "pbf", {})
  pbf.fix("vorticity", "vorticity", {})
  pbf.fix("xsph", "xsph", {})
end
pbf.fix("walls", "box", {})
-- The ramp, its slope towards the column, in the middle of the tank's floor and width.
pbf.fix("ramp", "solid", {file = here .. "geometry/wedge.stl", scale = {1.5, 1, 2.5}, translate = {0.6, 0.1, 0},
                          friction = var.friction or 0})

require("outputs").add(out, {color = "speed", min = 0, max = 3, direction = {0.5, 1.6, -1.5}})
pbf.compute("v", "speed")
pbf.compute("box", "extent")
pbf.thermo{every = math.max(1, math.floor(0.05 / dt)), columns = {"step", "time", "v.avg", "v.max", "box.xmax", "box.zmax"}}
pbf.run_until(t_end)
