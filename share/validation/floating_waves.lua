-- floating_waves.lua: a floating box in regular waves, the experiment of Ren, He, Dong & Wen (2015,
-- Applied Ocean Research 50:1-12), as a quasi-2D slab. A flume 0.4 m deep; a piston paddle at
-- x = 0 makes second-order Stokes waves H = 0.10 m, T = 1.2 s; a box 0.30 m long and 0.20 m high,
-- of density 500 kg/m^3, floats half submerged with its centre 1.8 m from the paddle, free to
-- surge, heave and roll; a beach rising 1:3.9 from x = 4.8 m breaks the waves. Measured motions:
-- ../shared/validation/ren_2015_floating_box_motion.csv (share/validate_floating_waves.sh,
-- share/validation/plot_floating_waves.py, docs/validation/floating_waves.md).
--
-- The wavemaker: second-order piston generation (Madsen 1971, as DualSPHysics's wave generator
-- has it), the paddle face at
--   X(t) = (S/2) sin(omega t) + X2 sin(2 omega t),   t from the paddle's start, no ramp,
--   S = H / m1,   m1 = 2 (cosh 2kh - 1) / (sinh 2kh + 2kh)         (Biesel's first-order H/S),
--   X2 = H^2 / (32 h) (3 cosh kh / sinh^3 kh - 2 / m1)              (the second-harmonic stroke),
--   omega^2 = g k tanh(kh);  here kh = 1.298, S = 0.0807 m, X2 = -0.32 mm.
--
-- The slab: `width` (default 4 spacings) across y, the domain's y faces free-slip walls, so that
-- the flow is 2D-like. The box spans the whole width, touching both y faces: it lies across two
-- symmetry planes and is held across them (free_translation {1, 0, 1}, free_rotation {0, 1, 0}),
-- with the mass and inertia of the slab's part (density 500 x 0.30 x 0.20 x width). Its centre
-- of mass is `cog` (default 5 mm, DualSPHysics's) above its geometric centre; inertia about it
-- that of a uniform box (Iyy = m (0.3^2 + 0.2^2) / 12).
--
-- Phases, in one run (scene time; the outputs count time from the paddle's start):
--   1. the fluid alone settles from its lattice for 0.8 s; the still-water level is measured by
--      gauges away from where the box will be (mean over 0.5 to 0.8 s);
--   2. the box is added (the fluid inside it left out) with its geometric centre at that level
--      (the draft of a density-500 box: half its height), held until `release` (1.0 s) while the
--      fluid settles around it, then released: it finds its own floating level (a few mm lower;
--      it is not the level's exact draft at this resolution) before the paddle starts;
--   3. at t = `settle` (1.5 s) the paddle starts; surge and heave count from the box's position
--      then, roll from its placement (level).
-- With PBF give -v settle=3: 0.2 s after the box's placing PBF's fluid moved at up to 7.5 m/s
-- around it, and 0.5 s after its release the box was still rocking (17 degrees, docs/validation/
-- floating_waves.md); WCSPH's box was at rest by 1.5 s.
-- With -v box=false there is no box, and a gauge at the box's x records the incident wave.
--
--   pbfengine run share/validation/floating_waves.lua [-v solver=wcsph|pbf|dfsph] [-v spacing=0.02]
--                                                     [-v t_end=9.0] [-v box=true] [-v out=out/waves]
--
-- Outputs (time t_s from the paddle's start): out/body.csv, the `body` compute every
-- `interval` s (default 1/60), with surge_m, heave_m (the centre's change since the release)
-- and roll_deg (ry, the turn about +y: positive turns z towards x, anticlockwise seen from +y);
-- out/gauges.csv, the gauges every `interval` s (depths, m); out/meta.txt, the set-up and the
-- measured level as key = value lines.
--
-- Variables: solver ("wcsph", the default, "pbf" or "dfsph"), spacing (m, default 0.02), support (kernel
-- radius in spacings, default 2.5), width (m, default 4 spacings), t_end (s after the paddle's
-- start, default 9.0), box (default true), out (default "out/waves"), height (H, m, default 0.10),
-- period (T, s, default 1.2), depth (m, default 0.4), order (1 or 2, default 2: the wavemaker's),
-- x_box (m from the paddle face, default 1.8), density (default 500), cog (m above the
-- geometric centre, default 0.005), settle (s, the paddle's start, default 1.5), release (s, the
-- box's, default 1.0), length (m, the flume, default 6.6),
-- beach (m, where the 1:3.9 beach starts, default 4.8; 0: none), damping (m, a damping zone over
-- the flume's last metres, default none), gauges (x list, m, default 1.0,3.0, plus 1.8 without
-- the box), interval (s, default 1/60), dt (s, default 0.025 h / sqrt(g depth); WCSPH's cfl takes
-- smaller steps; DFSPH's cfl steps up to 0.4 h / sqrt(2 g depth), as scenarios/wave_flume.lua). wcsph: alpha (default 0.02), density_form (default "continuity"), diffusion
-- (default 0): the flume's best waves (docs/validation/wave_flume.md). pbf: iterations (default 4),
-- one_sided (default true), xsph (default on), as scenarios/wave_flume.lua. dfsph: error,
-- divergence_error, max_iterations, nu (share/lua/solvers.lua). images, movie, vtk as in every
-- scenario.
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
package.path = here .. "../lua/?.lua;" .. package.path
local flag = require("flag")

local g = 9.81
local solver = var.solver or "wcsph"
assert(solver == "pbf" or solver == "wcsph" or solver == "dfsph",
       "solver must be pbf, wcsph or dfsph, got " .. tostring(solver))
local s = var.spacing or 0.02
local h = (var.support or 2.5) * s
local W = var.width or 4 * s
local d = var.depth or 0.4
local H, T = var.height or 0.10, var.period or 1.2
local order = var.order or 2
local t_end = var.t_end or 9.0
local out = var.out or "out/waves"
local with_box = flag(var.box, true, "box")
local x_box = var.x_box or 1.8
local Lb, Hb = 0.30, 0.20                 -- the box: length along x, height
local rho_b = var.density or 500
local cog = var.cog or 0.005
local settle = var.settle or 1.5
local release = var.release or 1.0
assert(release > 0.8 and release <= settle, "release must lie after 0.8 s (the box's placing) and not after settle")
local interval = var.interval or 1 / 60
local L, top = var.length or 6.6, d + 0.3
local back = 0.1                          -- room behind the paddle's face
local dt = var.dt or (solver == "dfsph" and 0.4 * h / math.sqrt(2 * g * d) or 0.025 * h / math.sqrt(g * d))

-- Linear dispersion, then the wavemaker.
local omega = 2 * math.pi / T
local k = omega * omega / g
for _ = 1, 100 do k = omega * omega / (g * math.tanh(k * d)) end
local kh = k * d
local m1 = 2 * (math.cosh(2 * kh) - 1) / (math.sinh(2 * kh) + 2 * kh)
local S = H / m1
local X2 = order >= 2 and H * H / (32 * d) * (3 * math.cosh(kh) / math.sinh(kh) ^ 3 - 2 / m1) or 0

pbf.domain{lo = {-back, 0, 0}, hi = {L, W, top}}
pbf.kernel_radius(h)
pbf.timestep(dt)
local n = pbf.lattice{lo = {0, 0, 0}, hi = {L, W, d}, spacing = s}
print(string.format("floating_waves (%s): %d particles, spacing %.4g m, h %.4g m, dt %.3g s; k %.4f 1/m (kh %.3f), stroke S %.5f m, X2 %.3e m, box %s",
                    solver, n, s, h, dt, k, kh, S, X2, tostring(with_box)))

pbf.fix("gravity", "gravity", {acceleration = {0, 0, -g}})
if solver == "wcsph" then
  require("solvers").wcsph{alpha = var.alpha or 0.02, density = var.density_form or "continuity", diffusion = var.diffusion or 0,
                           negative_pressure = var.negative_pressure}
elseif solver == "dfsph" then  -- its steps by the CFL bound, this dt the largest
  require("solvers").dfsph{error = var.error, divergence_error = var.divergence_error, nu = var.nu,
                           max_iterations = var.max_iterations}
else
  pbf.fix("pbf", "pbf", {iterations = var.iterations or 4, one_sided = flag(var.one_sided, true, "one_sided")})
  if (var.xsph or 1) ~= 0 then pbf.fix("xsph", "xsph", {}) end
end
pbf.fix("walls", "box", {})

-- The paddle: a box behind x = X(t), reaching beyond the side walls, floor and top (no face of it
-- along a domain face), still until `settle`.
local function paddle(t)
  local tau = math.max(0, t - settle)
  return {translate = {0.5 * S * math.sin(omega * tau) + X2 * math.sin(2 * omega * tau), 0, 0}}
end
pbf.fix("paddle", "solid", {shape = "box", lo = {-back - S, -h, -h}, hi = {0, W + h, top + h}, motion = paddle})
local x_beach = var.beach or 4.8
if x_beach > 0 then
  pbf.fix("beach", "solid", {shape = "plane", point = {x_beach, 0, 0}, normal = {-1, 0, 3.9}, friction = 20})
end
if var.damping and var.damping > 0 then
  pbf.fix("absorber", "damping", {from = {L - var.damping, 0, 0}, to = {L, 0, 0}})
end

-- Gauges (depths): the still level is measured at the "level" ones, away from the box.
local stations = {}
for x in tostring(var.gauges or "1.0,3.0"):gmatch("[^,%s]+") do
  stations[#stations + 1] = assert(tonumber(x), "gauges must be a list of x positions (m), like 1.0,3.0")
end
if not with_box then stations[#stations + 1] = x_box end
local feet, labels = {}, {}
for i, x in ipairs(stations) do
  feet[i] = {x, 0.5 * W, 0}
  labels[i] = string.format("x%03d", math.floor(100 * x + 0.5))
end
local level_feet = {{0.6, 0.5 * W, 0}, {1.2, 0.5 * W, 0}, {2.6, 0.5 * W, 0}, {3.5, 0.5 * W, 0}}
pbf.compute("eta", "gauge", {points = feet, labels = labels})
pbf.compute("level", "gauge", {points = level_feet, labels = {"l1", "l2", "l3", "l4"}})

-- 1. settle, measuring the still level over 0.5 to 0.8 s.
local acc = {sum = 0, n = 0, on = false}
pbf.every("level", 1, function()
  if acc.on then
    local v = pbf.value("level")
    acc.sum = acc.sum + (v.l1 + v.l2 + v.l3 + v.l4) / 4
    acc.n = acc.n + 1
  end
end)
pbf.run_until(0.5)
acc.on = true
pbf.run_until(0.8)
acc.on = false
pbf.unfix("level")
local level = acc.sum / acc.n

-- 2. the box, held until `release`.
local meta = {solver = solver, spacing = s, support = h / s, width = W, depth = d, height = H, period = T, order = order,
              k = k, stroke = S, X2 = X2, settle = settle, release = release, level = level, particles_lattice = n, length = L, beach = x_beach,
              box = tostring(with_box), x_box = x_box}
local columns = {"x", "y", "z", "vx", "vy", "vz", "rx", "ry", "rz", "wx", "wy", "wz", "fx", "fy", "fz", "tx", "ty", "tz"}
if with_box then
  local m = rho_b * Lb * Hb * W
  local zc = level                        -- a density-500 box floats with its centre at the level
  pbf.fix("box", "solid", {shape = "box", lo = {x_box - Lb / 2, 0, zc - Hb / 2}, hi = {x_box + Lb / 2, W, zc + Hb / 2},
                           mass = m, center_of_mass = {x_box, 0.5 * W, zc + cog},
                           inertia = {m * (W * W + Hb * Hb) / 12, m * (Lb * Lb + Hb * Hb) / 12, m * (Lb * Lb + W * W) / 12},
                           free_translation = {1, 0, 1}, free_rotation = {0, 1, 0}, hold = release})
  pbf.compute("body", "body", {solid = "box"})
  meta.mass = m
  meta.z_center = zc
  meta.cog = cog
  meta.Iyy = m * (Lb * Lb + Hb * Hb) / 12
end
print(string.format("floating_waves: still level %.5f m after settling (lattice %.3f m)%s", level, d,
                    with_box and string.format("; box of %.4g kg centred at z = %.5f m, held until %g s", meta.mass, level, release) or ""))

-- 3. the paddle starts and the box is released at t = settle; the samples count from there.
os.execute("mkdir -p '" .. out:gsub("'", "'\\''") .. "'")
local f_body = with_box and assert(io.open(out .. "/body.csv", "w")) or nil
local f_gauge = assert(io.open(out .. "/gauges.csv", "w"))
if f_body then f_body:write("t_s,", table.concat(columns, ","), ",surge_m,heave_m,roll_deg\n") end
f_gauge:write("t_s,", table.concat(labels, ","), "\n")
local next_t, x0, z0 = 0, nil, nil
pbf.every("record", 1, function(step, time)
  local tau = time - settle
  if tau < next_t - 1e-9 then return end
  next_t = next_t + interval
  if f_body then
    local b = pbf.value("body")
    if not x0 then x0, z0 = b.x, b.z; meta.x_start, meta.z_start, meta.ry_start = b.x, b.z, b.ry end
    local row = {}
    for i, c in ipairs(columns) do row[i] = string.format("%.7g", b[c]) end
    f_body:write(string.format("%.6f,", tau), table.concat(row, ","),
                 string.format(",%.7g,%.7g,%.7g\n", b.x - x0, b.z - z0, b.ry))
  end
  local e = pbf.value("eta")
  local row = {}
  for i, lab in ipairs(labels) do row[i] = string.format("%.6g", e[lab]) end
  f_gauge:write(string.format("%.6f,", tau), table.concat(row, ","), "\n")
end)

require("outputs").add(out, {color = "speed", min = 0, max = 0.5, direction = {0, 1, -0.12}, center = {2.0, 0.5 * W, 0.35},
                             zoom = 3, width = 1600, height = 480})
pbf.compute("v", "speed")
local cols = {"step", "time", "v.max", "eta." .. labels[1]}
if with_box then cols[#cols + 1] = "body.z"; cols[#cols + 1] = "body.ry" end
pbf.thermo{every = math.max(1, math.floor(0.25 / dt)), columns = cols}
local wall = os.time()
pbf.run_until(settle + t_end)
meta.particles = pbf.count()
meta.wall_s_after_settle = os.time() - wall
if f_body then f_body:close() end
f_gauge:close()
local f = assert(io.open(out .. "/meta.txt", "w"))
local keys = {}
for key in pairs(meta) do keys[#keys + 1] = key end
table.sort(keys)
for _, key in ipairs(keys) do f:write(key, " = ", tostring(meta[key]), "\n") end
f:close()
