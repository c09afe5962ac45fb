-- body_cost.lua: the dam break of compare_step.sh (a scene file of share/make_scene.py read
-- with pbf.read_scene; PBF with 4 iterations, vorticity, XSPH, box walls) with, by
-- -v obstacle=..., a block 8 x 20 x 10 cm on the floor just ahead of the column, where the
-- surge hits it within the 75 steps: "none" (no block), "solid" (a block at rest), "moving"
-- (a block a motion slides across the surge, 5 cm at 1 Hz) or "body" (a body of density 700
-- the surge pushes, resting on the floor: contacts and all). What each costs a step against
-- the analytic box alone. Run by share/benchmarks/body_cost.sh.
local init = var.init or error("missing variable 'init': give the scene file with -v init=PATH")
local scene = pbf.read_scene(init)
pbf.fix("gravity", "gravity", {acceleration = {0, 0, -9.81}})
pbf.fix("pbf", "pbf", {iterations = 4})
pbf.fix("vorticity", "vorticity", {})
pbf.fix("xsph", "xsph", {})
pbf.fix("walls", "box", {})
local s = pbf.kernel_radius() / 2
local block = {shape = "box", lo = {0.23, 0.4, s}, hi = {0.31, 0.6, s + 0.1}}
local obstacle = var.obstacle or "none"
if obstacle == "moving" then
  block.motion = function(t) return {translate = {0, 0.05 * math.sin(2 * math.pi * t), 0}} end
elseif obstacle == "body" then
  block.density = 700
elseif obstacle ~= "solid" and obstacle ~= "none" then
  error("obstacle must be none, solid, moving or body, got " .. tostring(obstacle))
end
if obstacle ~= "none" then pbf.fix("block", "solid", block) end
pbf.run_until(scene.t_final)
