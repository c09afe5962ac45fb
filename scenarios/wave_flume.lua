-- wave_flume.lua: a piston wavemaker in a narrow flume. Water d deep fills a flume 6 m long;
-- at x = 0 a vertical paddle (a `solid` box driven by a Lua function) moves back and forth
-- along x with stroke S (the full excursion) and period T. It starts once the water has
-- settled from its lattice (`start`, 1 s), its amplitude ramped up over two periods. The
-- waves run down the flume to a beach (a plane sloping 1:4 from x = 4.5 m) that breaks them,
-- and gauges at x = 0.6, 1 and 1.5 m record the free surface every 0.01 s. Linear wavemaker
-- theory (Dean & Dalrymple 1991, section 6.3) gives the height a piston makes in depth d:
--   H / S = 2 (cosh 2kd - 1) / (sinh 2kd + 2kd),   omega^2 = g k tanh(kd).
-- share/validation/wave_flume.py compares the gauges with it (docs/validation/wave_flume.md).
--
--   pbfengine run scenarios/wave_flume.lua [-v period=1.0] [-v stroke=0.04] [-v depth=0.3]
--                                          [-v spacing=0.02] [-v t_end=9] [-v out=out]
--   pbfengine run scenarios/wave_flume.lua -v images=0.1   (pictures, out/image_*.png)
--
-- The defaults make linear theory's wave (within 10% at x = 0.6 m, T = 1.0 and 1.4 s; about 7
-- minutes on 2 cores): WCSPH with alpha 0.02, the continuity density without diffusion (which
-- would damp the waves and lower the still level), and a kernel radius of 2.5 spacings (at 2
-- the waves run 8 to 12% fast, so the paddle makes them long and low). PBF (-v solver=pbf)
-- makes them 18% low at x = 0.6 m: its numerical damping (docs/validation/wave_flume.md).
--
-- Variables: period (s, default 1.0), stroke (m, default 0.04), depth (m, default 0.3),
-- spacing (m, default 0.02), support (the kernel's radius in spacings, default 2.5), width (m,
-- default 4 spacings: a 2D-like flume), start (s, when the paddle starts, default 1), t_end (s,
-- default 9), dt (s, default 0.025 h over the shallow-water wave speed; WCSPH's cfl takes
-- smaller steps; DFSPH's largest, 0.4 h over sqrt(2 g d)), solver ("wcsph", the default,
-- "pbf", or "dfsph": error, divergence_error, max_iterations and nu pass to it, its cfl
-- takes the steps), alpha (default 0.02), density
-- (default "continuity"), diffusion (default 0) and negative_pressure (wcsph's), iterations,
-- error, max_iterations, one_sided and xsph (pbf's, default 4 iterations, one-sided, XSPH on),
-- out (directory, default "out"; the gauges go to out/gauges.csv); images, movie and vtk as in
-- every scenario. For reflections: length (m, default 6: the flume's length), beach (default
-- true; false ends the flume in a vertical wall at x = length), damping (m, default none: a
-- damping zone over the flume's last `damping` metres), damping_rate (1/s, the `damping` fix's
-- default 10) and gauges (a list of x in m, default 0.6,1.0,1.5).
-- share/validation/flume_reflection.py measures the reflected wave with and without a damping
-- zone (docs/validation/flume_reflection.md).
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
package.path = here .. "../share/lua/?.lua;" .. package.path
local g = 9.81
local T = var.period or 1.0
local S = var.stroke or 0.04
local d = var.depth or 0.3
local s = var.spacing or 0.02
local W = var.width or 4 * s
local t_end = var.t_end or 9
local out = var.out or "out"
local solver = var.solver or "wcsph"
assert(solver == "pbf" or solver == "wcsph" or solver == "dfsph",
       "solver must be pbf, wcsph or dfsph, got " .. tostring(solver))
local L, top = var.length or 6.0, 2 * d  -- the flume, and the domain's height
local back = 0.1                       -- room behind the paddle's face (x < 0)
local h = (var.support or 2.5) * s   -- the kernel's radius
-- A small step: at 8 times this one PBF's waves lost a further fifth of their height (0.02 m).
-- DFSPH's cfl takes its steps up to 0.4 h per step at sqrt(2 g d), the dam break's: at the small
-- step it turns the walls' small density errors into a column that bounces (physics.md, "Known
-- limits of DFSPH").
local dt = var.dt or (solver == "dfsph" and 0.4 * h / math.sqrt(2 * g * d) or 0.025 * h / math.sqrt(g * d))

pbf.domain{lo = {-back, 0, 0}, hi = {L, W, top}}
pbf.kernel_radius(h)
pbf.timestep(dt)
local n = pbf.lattice{lo = {0, 0, 0}, hi = {L, W, d}, spacing = s}
print(string.format("wave_flume (%s): %d particles, spacing %.4g m, h %.4g m, dt %.3g s, period %g s, stroke %g m, depth %g m", solver, n,
                    s, h, dt, T, S, d))

pbf.fix("gravity", "gravity", {acceleration = {0, 0, -g}})
if solver == "wcsph" then
  require("solvers").wcsph{alpha = var.alpha or 0.02, density = var.density or "continuity",
                           diffusion = var.diffusion or 0, negative_pressure = var.negative_pressure}
elseif solver == "dfsph" then  -- its steps by the CFL bound, this dt the largest
  require("solvers").dfsph{error = var.error, divergence_error = var.divergence_error, nu = var.nu,
                           max_iterations = var.max_iterations}
else
  pbf.fix("pbf", "pbf", {iterations = var.iterations or 4, error = var.error, max_iterations = var.max_iterations,
                         one_sided = require("flag")(var.one_sided, true, "one_sided")})
  if (var.xsph or 1) ~= 0 then pbf.fix("xsph", "xsph", {}) end
end
pbf.fix("walls", "box", {})

-- The paddle: its face at x = X(t), X = (S/2) r(t) sin(2 pi t / T), r rising smoothly from 0 to
-- 1 over the first two periods.
local start = var.start or 1.0         -- the water settles from the lattice first
local ramp_time = 2 * T
local function paddle(t)
  local tau = math.max(0, t - start)
  local r = tau >= ramp_time and 1 or 0.5 * (1 - math.cos(math.pi * tau / ramp_time))
  return {translate = {0.5 * S * r * math.sin(2 * math.pi * tau / T), 0, 0}}
end
-- It reaches beyond the domain's side walls, floor and top, so that no face of it lies along a
-- domain face (a particle in such a corner would be pushed out along the wrong face).
pbf.fix("paddle", "solid", {shape = "box", lo = {-back - S, -h, -h}, hi = {0, W + h, top + h}, motion = paddle})
-- The beach: a plane rising 1 in 4 from the floor at x = 4.5 m (the fluid above it); with
-- -v beach=false the flume ends in the domain's vertical wall at x = L instead.
if require("flag")(var.beach, true, "beach") then
  pbf.fix("beach", "solid", {shape = "plane", point = {4.5, 0, 0}, normal = {-1, 0, 4}, friction = 20})
end
-- An optional damping zone (DualSPHysics's) over the last `damping` metres of the flume: the
-- velocities relax at up to `damping_rate` per second, growing as the square of the distance
-- from x = L - damping to x = L (fix `damping`). Off unless given: the beach already absorbs.
if var.damping and var.damping > 0 then
  pbf.fix("absorber", "damping", {from = {L - var.damping, 0, 0}, to = {L, 0, 0}, rate = var.damping_rate})
end

-- The gauges: x = 0.6, 1 and 1.5 m, or those listed in -v gauges=X1,X2,... (m).
local stations = {}
for x in tostring(var.gauges or "0.6,1.0,1.5"):gmatch("[^,%s]+") do
  stations[#stations + 1] = assert(tonumber(x), "gauges must be a list of x positions (m), like 0.6,1.0,1.5")
end
local feet, labels = {}, {}
for k, x in ipairs(stations) do
  feet[k] = {x, 0.5 * W, 0}
  labels[k] = string.format("x%03d", math.floor(100 * x + 0.5))  -- x060: the gauge at x = 0.60 m
end
pbf.compute("eta", "gauge", {points = feet, labels = labels})
pbf.fix("gauges", "sample", {computes = {"eta"}, interval = 0.01, file = out .. "/gauges.csv"})

-- Pictures from the side, of the paddle and the first 3 m, where the gauges stand.
require("outputs").add(out, {color = "speed", min = 0, max = 0.3, direction = {0, 1, -0.12}, center = {1.45, 0.5 * W, 0.3},
                             zoom = 4, width = 1600, height = 480})
pbf.compute("v", "speed")
pbf.thermo{every = math.max(1, math.floor(0.25 / dt)), columns = {"step", "time", "v.max", "eta." .. labels[1], "eta." .. labels[math.min(2, #labels)]}}
pbf.run_until(t_end)
