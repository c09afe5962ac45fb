-- channel.lua: open-channel flow over an obstacle. Water enters a channel 1 m long and 0.1 m
-- wide through its upstream end (an emitter: a rectangle the channel's width and 3 cm deep,
-- facing downstream, at 1 m/s, with an inlet zone), runs along the floor, over a bump (a solid
-- box 1 cm high),
-- and leaves through the open downstream end (the box fix with `open = {"x+"}`): a free
-- overfall. The inflow is supercritical (Froude number U / sqrt(g d) = 1.8) and the bump low
-- enough not to choke it (its height below the inflow's specific energy less the critical
-- depth's, 1.5 (q^2/g)^(1/3): 1.35 cm), so the water runs over it without backing up. After
-- a second the channel holds a steady flow, as much leaving as entering (thermo: `n`, what
-- came in, `in.count`, and what left, `out.count`; gauges `depth.up` and `depth.down`).
--
--   pbfengine run scenarios/channel.lua [-v t_end=3] [-v out=out] [-v solver=pbf|wcsph]
--
-- Variables: t_end (simulated seconds, default 3), s (particle spacing, default 0.01 m),
-- speed (the inflow's, default 1 m/s), bump (the obstacle's height, default 0.01 m; 0 for
-- none), out (frame directory, default "out"; "" for none), interval (seconds between frames,
-- default 0.02), solver ("pbf", default, or "wcsph"; share/lua/solvers.lua). Pictures, a movie
-- and ParaView frames with -v images=T, -v movie=PATH, -v vtk=T (share/lua/outputs.lua);
-- restarts every restart_interval seconds (default 0.5; 0 for none), -v restart=FILE
-- continues from one.
package.path = (debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./") .. "../share/lua/?.lua;" .. package.path
local solver = var.solver or "pbf"
assert(solver == "pbf" or solver == "wcsph", "solver must be pbf or wcsph, got " .. tostring(solver))
local t_end = var.t_end or 3
local out = var.out or "out"
local s = var.s or 0.01
local speed = var.speed or 1.0
local bump = var.bump or 0.01
local L, W, H, inflow_depth = 1.0, 0.1, 0.25, 0.03
local g = 9.81

local scene = pbf.scene(function()
  pbf.domain{lo = {0, 0, 0}, hi = {L, W, H}}
  pbf.kernel_radius(2 * s)
  pbf.timestep(0.4 * 2 * s / math.sqrt(2 * g * H))   -- 0.4 h per step at the speed of a fall from the top
end)

pbf.fix("gravity", "gravity", {acceleration = {0, 0, -g}})
if solver == "wcsph" then
  require("solvers").wcsph{sound_speed = 10 * math.sqrt(speed ^ 2 + 2 * g * inflow_depth), density = "continuity",
                           diffusion = 0.1}
else
  pbf.fix("pbf", "pbf", {iterations = 4})
  pbf.fix("xsph", "xsph", {c = 0.01})
end
pbf.fix("walls", "box", {open = {"x+"}})
if bump > 0 then
  pbf.fix("bump", "solid", {shape = "box", lo = {0.5, -0.01, -0.01}, hi = {0.56, W + 0.01, bump}})
end
-- The inflow: the channel's width along y (its first side), inflow_depth along z, against the
-- upstream wall (half a spacing from it, where the wall holds particles), with an inlet zone
-- 4 spacings deep moving at the inflow's speed, so that the water ahead neither blocks the
-- opening nor flows back over it.
pbf.fix("inlet", "emitter", {center = {s / 2, W / 2, inflow_depth / 2}, normal = {1, 0, 0}, axis = {0, 1, 0},
                             size = {W, inflow_depth}, speed = speed, spacing = s, buffer = 4 * s})

require("outputs").add(out, {color = "speed", min = 0, max = 1.5, direction = {0.25, 1.5, -0.6}, zoom = 1.2})
require("outputs").frames(out, 0.5)

pbf.compute("n", "count")
pbf.compute("in", "flow", {fix = "inlet"})
pbf.compute("out", "flow", {fix = "walls"})
pbf.compute("depth", "gauge", {points = {{0.3, W / 2, 0}, {0.8, W / 2, 0}}, labels = {"up", "down"}})
pbf.compute("front", "front", {axis = "x", percentile = 100})
pbf.thermo{every = math.max(1, math.floor(0.05 / pbf.timestep() + 0.5)),
           csv = var.csv or (out ~= "" and out .. "/thermo.csv" or nil),
           columns = {"step", "time", "n", "in.count", "out.count", "in.mass", "out.mass", "depth.up", "depth.down",
                      "front"}}

print(string.format("channel (%s): a %.3g m/s inflow %.3g m deep over a %.3g m bump, to t = %g s", solver, speed,
                    inflow_depth, bump, t_end))
if scene.restart then print("continuing from " .. scene.restart) end
pbf.run_until(t_end)
