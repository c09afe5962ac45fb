-- fountain.lua: a fountain playing into a basin with a drain. A jet leaves a nozzle (an
-- emitter: a disc 3 cm across, 1.6 cm above the pool) at 2 m/s, leaning 30 degrees from
-- the vertical, arcs over and falls into the pool; a drain in the far corner of the basin's
-- floor (an outflow region) takes the water away. The drain takes more the deeper the water
-- stands over it, so the pool settles where it takes what the jet brings: after a second or
-- so the particle count stays level (thermo: `n`, and the flow computes `in` and `out`, whose
-- difference is what the pool gained since the start).
--
--   pbfengine run scenarios/fountain.lua [-v t_end=3] [-v out=out] [-v solver=pbf|wcsph]
--
-- Variables: t_end (simulated seconds, default 3), s (particle spacing, default 0.01 m),
-- speed (the jet's, default 2 m/s), drain (the drain's side, default 0.025 m), out (frame
-- directory, default "out"; "" for none), interval (seconds between frames, default 0.02),
-- solver ("pbf", default, or "wcsph"; share/lua/solvers.lua). Pictures, a movie and ParaView
-- frames with -v images=T, -v movie=PATH, -v vtk=T (share/lua/outputs.lua); restarts every
-- restart_interval seconds (default 0.5; 0 for none), and -v restart=FILE continues from one.
package.path = (debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./") .. "../share/lua/?.lua;" .. package.path
local solver = var.solver or "pbf"
assert(solver == "pbf" or solver == "wcsph", "solver must be pbf or wcsph, got " .. tostring(solver))
local t_end = var.t_end or 3
local out = var.out or "out"
local s = var.s or 0.01
local speed = var.speed or 2.0
local drain = var.drain or 0.025
local L, W, H, depth = 0.5, 0.3, 0.5, 0.06   -- the basin, and the pool's starting depth
local g = 9.81
local lean = math.rad(30)

local scene = pbf.scene(function()
  pbf.domain{lo = {0, 0, 0}, hi = {L, W, H}}
  pbf.kernel_radius(2 * s)
  pbf.timestep(0.4 * 2 * s / speed)   -- 0.4 h per step at the jet's speed
  pbf.lattice{lo = {0, 0, 0}, hi = {L, W, depth}, spacing = s}
end)

pbf.fix("gravity", "gravity", {acceleration = {0, 0, -g}})
if solver == "wcsph" then
  -- The sound speed for the fastest water: the jet, and what it gains falling back.
  require("solvers").wcsph{sound_speed = 10 * math.sqrt(speed ^ 2 + 2 * g * 0.2), density = "continuity",
                           diffusion = 0.1}
else
  pbf.fix("pbf", "pbf", {iterations = 4})
  pbf.fix("xsph", "xsph", {c = 0.01})
end
pbf.fix("walls", "box", {})
pbf.fix("nozzle", "emitter", {shape = "disc", center = {0.08, W / 2, depth + 0.016}, radius = 0.015,
                              normal = {math.sin(lean), 0, math.cos(lean)}, speed = speed, spacing = s})
pbf.fix("drain", "outflow", {region = "box", lo = {L - drain, W / 2 - drain / 2, 0},
                             hi = {L, W / 2 + drain / 2, 2 * s}})

require("outputs").add(out, {color = "speed", min = 0, max = speed, direction = {0.6, 1.6, -0.9}, zoom = 1.2})
require("outputs").frames(out, 0.5)

pbf.compute("n", "count")
pbf.compute("in", "flow", {fix = "nozzle"})
pbf.compute("out", "flow", {fix = "drain"})
pbf.compute("top", "extent")
pbf.compute("err", "density_error")
pbf.thermo{every = math.max(1, math.floor(0.05 / pbf.timestep() + 0.5)),
           csv = var.csv or (out ~= "" and out .. "/thermo.csv" or nil),
           columns = {"step", "time", "n", "in.count", "out.count", "in.mass", "out.mass", "top.zmax", "err.avg"}}

print(string.format("fountain (%s): %d particles in the pool, a %.3g m/s jet, to t = %g s", solver, pbf.count(),
                    speed, t_end))
if scene.restart then print("continuing from " .. scene.restart) end
pbf.run_until(t_end)
