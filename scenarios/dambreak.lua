-- dambreak.lua: the 3D dam break of Martin & Moyce (1952). A water column a wide (x) and
-- 2a high (z; `-v height=1` for their square column), against the wall x = 0 of a tank 5a
-- long and 4a high, is released at t = 0, surges along the floor, runs up the far wall and
-- falls back. Thermo tracks the surge front (`front`: the 99th percentile of x, or `-v
-- percentile=P`; `far`: the farthest particle) and the water's height at the back wall
-- (`back`) every 0.01 s (`-v thermo=SECONDS`) so that Z = front / a against T = t sqrt(2 g / a)
-- can be compared with the experiment (share/plot_front.py, share/validation/martin_moyce.py); text frames go to out/
-- (share/render_frames.py --box 0.5 0.05 0.4 makes pictures and a movie).
--
--   pbfengine run scenarios/dambreak.lua [-v particles=30000] [-v t_end=1.0] [-v out=out]
--   pbfengine run scenarios/dambreak.lua -v restart=out/restart.400.restart   (continue to t_end)
--
-- Variables: particles (about how many, default 30000), t_end (simulated seconds, default
-- 1.0), a (column width in m, default 0.1), height (column height in a, default 2), out (frame directory, default "out"; "" for
-- none), interval (seconds between frames, default 0.02), csv (thermo CSV, default
-- out/thermo.csv), iterations (default 4), vorticity (confinement epsilon, default 0.05),
-- xsph (XSPH c, default 0.01); one_sided, wall_density (true/false), scorr_k, relaxation,
-- error and max_iterations (an accuracy target), contact and friction (the walls') to
-- compare the solver variants of docs/physics.md (default: the styles' defaults, pbfengine
-- help pbf); dt_iterations: PBF's time step chosen by fix cfl, the largest in which the
-- accuracy target `error` takes at most that many iterations (with courant, default 0.4, and
-- max_dt). support: the kernel radius h in spacings (default 2). periodic: axes along which
-- the tank repeats ("y": an endless tank's quasi-2D flow). solver: "pbf" (default) or
-- "wcsph", weakly compressible SPH (share/lua/solvers.lua; 8000 particles by default, as its steps
-- are set by the sound speed: alpha, eos, sound_speed, courant and fixed_dt pass to it; scenarios/dambreak_wcsph.lua runs it),
-- or "dfsph", divergence-free SPH (its steps by the CFL bound, dt the largest: error,
-- divergence_error, max_iterations, nu, courant and fixed_dt pass to it).
-- flap: a gate hinged along its top edge across the tank, 3a from the back wall (a body the
-- surge swings open; docs/user-guide.md#bodies): its density in kg/m^3 (-v flap=800), a tall,
-- a/10 thick, its lower edge a/4 above the floor; thermo's `flap` column is its angle (degrees).
-- Output beyond the text frames: images (seconds between PNG pictures, out/image_*.png),
-- movie (an mp4 path, 50 pictures per simulated second), vtk (seconds between ParaView
-- frames, out/vtk/frame_*.vtu and out/vtk/frame.pvd).
-- Restarts: out/restart.STEP.restart every restart_interval seconds (default 0.25; 0 for
-- none) or every restart_every steps, the newest two kept, and one on Ctrl-C; restart=FILE
-- continues from one (the scene comes from the file, the pipeline from this script, and the
-- run goes on to t_end).
package.path = (debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./") .. "../share/lua/?.lua;" .. package.path
local flag, axes = require("flag"), require("axes")
local solver = var.solver or "pbf"
assert(solver == "pbf" or solver == "wcsph" or solver == "dfsph",
       "solver must be pbf, wcsph or dfsph, got " .. tostring(solver))
local N = var.particles or (solver == "wcsph" and 8000 or 30000)
local t_end = var.t_end or 1.0
local a = var.a or 0.1
local out = var.out or "out"
local g = 9.81

-- Column a x (a/2) x 2a: N = (a/s)^3 particles at spacing s (half that for the square
-- column); kernel radius h = 2 s.
local layers = math.max(4, math.floor((N) ^ (1 / 3) + 0.5))
local s = a / layers
local h = (var.support or 2) * s   -- the kernel radius, in spacings
local depth = layers // 2 * s
local height = (var.height or 2) * a   -- Martin & Moyce's columns: 2a (n^2 = 2) and a (n^2 = 1)
if not (height > 0 and height < 4 * a) then
  error(string.format("height must be above 0 and below 4 (the tank is 4a high), got %s", tostring(var.height)), 0)
end
if var.thermo and not (var.thermo > 0) then
  error(string.format("thermo must be a positive time (s), got %s", tostring(var.thermo)), 0)
end
local dt = var.dt or 0.4 * h / math.sqrt(2 * g * height)   -- 0.4 h per step at the free-fall speed
-- WCSPH steps are set by the sound speed c0 = 10 sqrt(2 g 2a) (fix cfl; dt above is their bound)
local dt_typical = solver == "wcsph" and 0.15 * h / (10 * math.sqrt(2 * g * height)) or dt

-- The scene, or with -v restart=FILE the scene saved in FILE (domain, h, dt, particles, step
-- and time): pbf.scene reads it and does not call the function.
local scene = pbf.scene(function()
  pbf.domain{lo = {0, 0, 0}, hi = {5 * a, depth, 4 * a}, periodic = axes(var.periodic)}   -- tall enough for the run-up
  pbf.kernel_radius(h)
  pbf.timestep(dt)
  pbf.lattice{lo = {0, 0, 0}, hi = {a, depth, height}, spacing = s}
end)
if scene.restart then
  if var.dt then pbf.timestep(var.dt) end   -- a new step size: no longer the saved run's continuation
  dt = pbf.timestep()
end

pbf.fix("gravity", "gravity", {acceleration = {0, 0, -g}})
if solver == "wcsph" then
  require("solvers").wcsph{alpha = var.alpha, eos = var.eos, density = var.density, fixed_dt = var.fixed_dt,
                           sound_speed = var.sound_speed, courant = var.courant}
elseif solver == "dfsph" then
  require("solvers").dfsph{error = var.error, divergence_error = var.divergence_error, max_iterations = var.max_iterations,
                           nu = var.nu, courant = var.courant, fixed_dt = var.fixed_dt,
                           align = out ~= "" and (var.interval or 0.02) or nil}
else
  pbf.fix("pbf", "pbf", {iterations = var.iterations, relaxation = var.relaxation, one_sided = flag(var.one_sided, true, "one_sided"),
                         scorr_k = var.scorr_k, error = var.error, max_iterations = var.max_iterations})
  pbf.fix("vorticity", "vorticity", {epsilon = var.vorticity or 0.05})
  pbf.fix("xsph", "xsph", {c = var.xsph or 0.01})
  if var.dt_iterations then  -- the largest step in which pbf reaches `error` within dt_iterations
    pbf.fix("cfl", "cfl", {iterations = var.dt_iterations, courant = var.courant or 0.4,
                           max_dt = var.max_dt, align = out ~= "" and (var.interval or 0.02) or nil})
  end
end
pbf.fix("walls", "box", {wall_density = flag(var.wall_density, true, "wall_density"), contact_distance = var.contact,
                         friction = var.friction})
-- Pictures, movie and ParaView frames on request (share/lua/outputs.lua).
require("outputs").add(out, {color = "speed", min = 0, max = 2.5, direction = {1, 2.2, -0.9}, zoom = 1.4})
require("outputs").frames(out, 0.25)

local columns = {"step", "time", "dt", "front", "far", "back", "err.avg", "err.max", "err.compression", "ke"}
if var.flap then
  local t = math.max(2 * s, a / 10)
  pbf.fix("flap", "solid", {shape = "box", lo = {3 * a - t / 2, 0, a / 4}, hi = {3 * a + t / 2, depth, 1.25 * a},
                            density = var.flap, free_rotation = {0, 1, 0}, hinge = {3 * a, depth / 2, 1.25 * a}})
  pbf.compute("gate", "body", {solid = "flap"})
  columns[#columns + 1] = "gate.ry"
end
pbf.compute("err", "density_error")
pbf.compute("front", "front", {axis = "x", percentile = var.percentile or 99})
pbf.compute("far", "front", {axis = "x", percentile = 100})
pbf.compute("back", "gauge", {points = {{0, depth / 2, 0}}})   -- the water's height at the back wall
pbf.compute("ke", "kinetic_energy")
pbf.thermo{every = math.max(1, math.floor((var.thermo or 0.01) / dt_typical)),
           -- a continued run keeps the first run's rows before the restart and writes the rest again
           csv = var.csv or (out ~= "" and out .. "/thermo.csv" or nil),
           columns = columns}

print(string.format("dam break (%s): %d particles, a = %g m, h %.4g m, dt %s%.4g s, to t = %g s", solver,
                    pbf.count(), a, pbf.kernel_radius(), solver ~= "pbf" and "<= " or "", dt, t_end))
pbf.run_until(t_end)
