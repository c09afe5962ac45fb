-- hydrostatic.lua: a column of water at rest in a closed box. It should stay at rest: the
-- column keeps its height, the density error stays small and no particle moves much. The
-- test of the density solver and the walls under gravity.
--
--   pbfengine run scenarios/hydrostatic.lua [-v particles=8000] [-v t_end=2] [-v csv=FILE]
--
-- Variables: particles (about how many, default 8000), t_end (simulated seconds, default
-- 2), height (column height in m, default 0.4), width (side of the square footprint in m,
-- default height/2),
-- iterations, error (an accuracy target instead of a fixed count), max_iterations, relaxation,
-- epsilon, one_sided, wall_density, contact (the walls' contact_distance) and scorr_k (default: the styles' defaults, see
-- pbfengine help pbf), xsph (XSPH c, default 0.01), dt (default 0.4 h / sqrt(2 g H)),
-- csv (thermo CSV file, default none), out (frame directory, default none), solver ("pbf",
-- the default; "wcsph": weakly compressible SPH, with alpha; "dfsph": divergence-free SPH, with
-- error (default 1e-5), divergence_error (1e-4), max_iterations (1000) and nu; both
-- share/lua/solvers.lua),
-- periodic (axes along which the domain repeats, e.g. "xy": a layer of water without side
-- walls, whose lattice tiles the period).
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
package.path = here .. "../share/lua/?.lua;" .. package.path
local geometry = here .. "geometry/"
local flag = require("flag")
local axes = require("axes")
local N = var.particles or 8000
local t_end = var.t_end or 2.0
local H = var.height or 0.4
local W = var.width or H / 2
local s = (W * W * H / N) ^ (1 / 3)        -- lattice spacing
s = W / math.floor(W / s + 0.5)             -- a whole number of layers across
local h = 2 * s                             -- kernel radius
local dt = var.dt or 0.4 * h / math.sqrt(2 * 9.81 * H)

pbf.domain{lo = {0, 0, 0}, hi = {W, W, 1.5 * H}, periodic = axes(var.periodic)}
pbf.kernel_radius(h)
pbf.timestep(dt)
pbf.lattice{lo = {0, 0, 0}, hi = {W, W, H}, spacing = s}

pbf.fix("gravity", "gravity", {})
local solver = var.solver or "pbf"
if solver == "wcsph" then
  require("solvers").wcsph{alpha = var.alpha, density = var.density, fixed_dt = var.fixed_dt}
elseif solver == "dfsph" then  -- tolerances tighter than the style's: a still column (docs/validation/dfsph.md)
  require("solvers").dfsph{error = var.error or 1e-5, divergence_error = var.divergence_error or 1e-4,
                           max_iterations = var.max_iterations or 1000, nu = var.nu, fixed_dt = var.fixed_dt}
else
  pbf.fix("pbf", "pbf", {iterations = var.iterations, error = var.error, max_iterations = var.max_iterations,
                         epsilon = var.epsilon, relaxation = var.relaxation, one_sided = flag(var.one_sided, true, "one_sided"),
                         scorr_k = var.scorr_k})
  pbf.fix("xsph", "xsph", {c = var.xsph or 0.01})
end
if (var.walls or "box") == "box" then
  pbf.fix("walls", "box", {wall_density = flag(var.wall_density, true, "wall_density"), contact_distance = var.contact})
else  -- the same box as a solid container: a primitive, or a mesh file read with Assimp
  local tank = {fluid = "inside", wall_density = flag(var.wall_density, true, "wall_density"), contact_distance = var.contact}
  if var.walls == "mesh" then
    tank.file = geometry .. "unit_box.obj"
    tank.scale = {W, W, 1.5 * H}
  else
    tank.shape, tank.lo, tank.hi = "box", {0, 0, 0}, {W, W, 1.5 * H}
  end
  pbf.fix("walls", "solid", tank)
end
if var.out then pbf.fix("frames", "dump/text", {path = var.out .. "/frame_*.txt", interval = var.frame_interval or 0.05}) end

pbf.compute("err", "density_error")
pbf.compute("ke", "kinetic_energy")
pbf.compute("v", "speed")
pbf.compute("top", "front", {axis = "z", percentile = 99})
pbf.compute("box", "extent")
-- WCSPH steps are set by the sound speed c0 = 10 sqrt(2 g H) (fix cfl), not by dt above
local dt_typical = solver == "wcsph" and 0.15 * h / (10 * math.sqrt(2 * 9.81 * H)) or dt
local columns = {"step", "time", "err.avg", "err.max", "err.compression", "v.avg", "v.max", "top", "box.zmin"}
if solver ~= "wcsph" then  -- the constraint iterations per step, averaged over each line's steps
  pbf.compute("it", "iterations")
  columns[#columns + 1] = "it.avg"
end
if solver == "dfsph" then  -- and the divergence-free solve's
  pbf.compute("div", "iterations", {loop = "divergence"})
  columns[#columns + 1] = "div.avg"
end
pbf.thermo{every = math.max(1, math.floor(0.1 / dt_typical)), csv = var.csv, columns = columns}

print(string.format("hydrostatic: %d particles, spacing %.4g m, h %.4g m, dt %.4g s", pbf.count(), s, h, dt))
pbf.run_until(t_end)
