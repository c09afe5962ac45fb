-- flow_cost.lua: the dam break of compare_step.sh (a scene file of share/make_scene.py read
-- with pbf.read_scene; PBF with 4 iterations, vorticity, XSPH, box walls) with, when -v flow=1,
-- a small emitter over the far end (a 4 x 4 spacing opening facing down, 1 m/s) and a sink
-- over the floor below it: what emitting and removing add to a step of a scene that does not
-- otherwise use them. Run by share/benchmarks/flow_cost.sh.
local init = var.init or error("missing variable 'init': give the scene file with -v init=PATH")
local scene = pbf.read_scene(init)
local L = scene.L
pbf.fix("gravity", "gravity", {acceleration = {0, 0, -9.81}})
pbf.fix("pbf", "pbf", {iterations = 4})
pbf.fix("vorticity", "vorticity", {})
pbf.fix("xsph", "xsph", {})
pbf.fix("walls", "box", {})
if (var.flow or 0) == 1 then
  local s = pbf.kernel_radius() / 2
  pbf.fix("jet", "emitter", {center = {0.9 * L, L / 2, 0.15 * L}, normal = {0, 0, -1}, size = {4 * s, 4 * s}, speed = 1})
  pbf.fix("drain", "outflow", {region = "box", lo = {0.85 * L, 0.45 * L, 0}, hi = {0.95 * L, 0.55 * L, 2 * s}})
end
pbf.run_until(scene.t_final)
