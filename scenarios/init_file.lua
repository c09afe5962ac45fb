-- init_file.lua: runs a scene file in the original study's format (share/make_scene.py
-- writes them) with the standard PBF pipeline: gravity -9.81 m/s^2 along z, the pbf density
-- constraint, box walls on [0, L]^3, vorticity confinement and XSPH viscosity, from t = 0
-- until the file's final time, writing frames DIR/frame_NNNNN.txt at its output interval.
--
--   pbfengine run scenarios/init_file.lua -v init=PATH [-v out=DIR] [-v iterations=N]
--
-- Variables: init (the scene file, required), out (frame directory, default "out"),
-- walls ("box", the default: the analytic box fix; "mesh": the same box as a container read
-- from scenarios/geometry/unit_box.obj; "solid": the same as a box primitive),
-- iterations (constraint iterations per step, default 4), solver ("pbf", the default, or
-- "wcsph": weakly compressible SPH, or "dfsph": divergence-free SPH, share/lua/solvers.lua;
-- the file's time step is then an upper bound, the CFL control takes smaller steps as needed,
-- and ends steps on the output interval so that frames stay on it).
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
package.path = here .. "../share/lua/?.lua;" .. package.path
local init = var.init or error("missing variable 'init': give the scene file with -v init=PATH")
local out = var.out or "out"
local iterations = var.iterations or 4

local scene = pbf.read_scene(init)   -- sets the domain [0, L]^3, h and the time step

pbf.fix("gravity", "gravity", {acceleration = {0, 0, -9.81}})
local solver = var.solver or "pbf"
if solver == "wcsph" then
  require("solvers").wcsph{align = scene.interval}
elseif solver == "dfsph" then
  require("solvers").dfsph{align = scene.interval}
else
  pbf.fix("pbf", "pbf", {iterations = iterations})
  pbf.fix("vorticity", "vorticity", {})
  pbf.fix("xsph", "xsph", {})
end
if (var.walls or "box") == "box" then
  pbf.fix("walls", "box", {})
else  -- the same walls as a container read from a mesh file ("mesh") or a primitive ("solid")
  local tank = {fluid = "inside"}
  if var.walls == "mesh" then
    tank.file, tank.scale = here .. "geometry/unit_box.obj", scene.L
  else
    tank.shape, tank.lo, tank.hi = "box", {0, 0, 0}, {scene.L, scene.L, scene.L}
  end
  pbf.fix("walls", "solid", tank)
end
pbf.fix("frames", "dump/text", {path = out .. "/frame_*.txt", interval = scene.interval})

pbf.compute("err", "density_error")
pbf.thermo{every = 100, columns = {"step", "time", "err.avg", "err.max"}}

-- The first step whose time reaches the final time is the last (n dt >= t_final).
pbf.run_until(scene.t_final)
