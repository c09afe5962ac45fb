-- heave_decay.lua: the heave decay of a floating sphere, Kramer et al. (2021), as a QUARTER model.
-- A sphere of diameter D = 0.3 m and mass 7.056 kg floats half submerged in water of density
-- 998.2 kg/m^3 (g = 9.82 m/s^2); released from rest with its centre H0 above its equilibrium it
-- moves in heave only and its oscillation decays as it radiates waves
-- (../shared/validation/kramer_2021_sphere_heave_decay_*.csv; share/validate_heave_decay.sh
-- compares z(t)/z(0) with the measured mean against t/0.7561 s, docs/validation/heave_decay.md).
--
-- The quarter model: the sphere's centre stands on the domain's corner x = 0, y = 0 and the box's
-- walls there, free-slip, are the two symmetry planes; the body is given a quarter of the mass
-- (the fluid only presses on the quarter inside the domain; the sphere reaches outside it, which
-- is allowed). Heave only: free_translation {0, 0, 1}, free_rotation {0, 0, 0}. The basin is
-- basin x basin (m) of that quarter, depth `depth`, with a damping zone over its last `damping`
-- metres along x and along y, so that the radiated wave does not come back.
--
-- Three phases, in one run:
--   1. settle: the fluid alone settles from its lattice for `settle` s; the still-water level is
--      measured (compute `gauge` at five points away from the sphere, mean over the last 40%);
--   2. hold: the sphere is added (the fluid inside it is left out) with its centre at the level
--      where it will float, plus H0, and held there for `hold` s while the fluid settles around it;
--      the level is measured again (last 50% of the hold), and the fluid's force on the held body;
--   3. release: the body moves; its state is sampled every `interval` s for `t_end` s.
-- Equilibrium: the centre at the still-water level once the sphere floats half submerged. In a
-- finite basin that level depends on the sphere's position (the water it displaces raises it), so
-- it is computed from the level measured during the hold with the sphere at offset a above it:
--   z_eq = level_hold + (V_q(0) - V_q(a)) / basin^2,
-- V_q(a) = the quarter sphere's volume below the surface with its centre a above it (a spherical
-- cap; water volume conserved); H0m = z_centre - z_eq is the measured initial offset, as the
-- experiment's x3/H0m normalises by the measured one. The placement aims at H0m = H0 with the
-- settle run's level. The fluid's buoyancy on the held sphere is compared with rho0 g V_q(a).
--
--   pbfengine run share/validation/heave_decay.lua [-v solver=pbf] [-v h0=0.3] [-v spacing=0.015]
--                                                    [-v t_end=2] [-v out=out/heave]
--
-- Variables: solver ("pbf", the default, or "wcsph"), h0 (H0 / D, default 0.3), spacing (m,
-- default 0.015 for pbf, 0.025 for wcsph), t_end (s after the release, default 2.0), out
-- (directory, default "out/heave": body.csv, the body every `interval` s, time from the scene's
-- start; levels.csv, the gauges; meta.txt, the measured levels, placement and hold force as
-- key = value lines). Set-up: depth (m, default 0.6), basin (m, default 0.75), damping (m, default
-- 0.25; 0: none), damping_rate (1/s, default 10), settle (s, default 0.6), hold (s, default 0.4),
-- interval (s, default 0.004), mass (kg of the quarter body, default 7.056 / 4), rho0 (default
-- 998.2), g (default 9.82), support (kernel radius in spacings, default 2 for pbf, 2.5 for wcsph),
-- dt (s, default 0.4 h / sqrt(2 g depth) for pbf; wcsph's cfl chooses its own, this its bound).
-- pbf: iterations (default 4), xsph (XSPH c, default 0.01; 0: off), one_sided. wcsph: alpha
-- (default 0.02), density (default "continuity"), diffusion (default 0.1), sound_speed, courant
-- (the least damped WCSPH of the standing-wave test, docs/validation/wave_flume.md).
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
package.path = here .. "../lua/?.lua;" .. package.path
local flag = require("flag")

local solver = var.solver or "pbf"
assert(solver == "pbf" or solver == "wcsph", "solver must be pbf or wcsph, got " .. tostring(solver))
local D, R = 0.3, 0.15
local ratio = var.h0 or 0.3
local H0 = ratio * D
local s = var.spacing or (solver == "pbf" and 0.015 or 0.025)
local h = (var.support or (solver == "pbf" and 2 or 2.5)) * s
local d = var.depth or 0.6
local L = var.basin or 0.75
local rho0 = var.rho0 or 998.2
local g = var.g or 9.82
local mass = var.mass or 7.056 / 4
local t_settle, t_hold = var.settle or 0.6, var.hold or 0.4
local t_end = var.t_end or 2.0
local interval = var.interval or 0.004
local out = var.out or "out/heave"
local top = d + 0.45                         -- room above for the sphere at H0 = 0.5 D and splashes
local dt = var.dt or 0.4 * h / math.sqrt(2 * g * d)

pbf.domain{lo = {0, 0, 0}, hi = {L, L, top}}
pbf.kernel_radius(h)
pbf.timestep(dt)
pbf.rest_density(rho0)
local n = pbf.lattice{lo = {0, 0, 0}, hi = {L, L, d}, spacing = s}
print(string.format("heave_decay (%s): %d particles, spacing %.4g m, h %.4g m, dt %.4g s, H0 %.3g D, basin %g m, depth %g m",
                    solver, n, s, h, dt, ratio, L, d))

pbf.fix("gravity", "gravity", {acceleration = {0, 0, -g}})
if solver == "wcsph" then
  -- The least damped WCSPH the standing wave measured (docs/validation/wave_flume.md).
  require("solvers").wcsph{alpha = var.alpha or 0.02, density = var.density or "continuity", diffusion = var.diffusion or 0.1,
                           sound_speed = var.sound_speed, courant = var.courant,
                           negative_pressure = var.negative_pressure}
else
  pbf.fix("pbf", "pbf", {iterations = var.iterations or 4, one_sided = flag(var.one_sided, true, "one_sided")})
  if (var.xsph or 0.01) > 0 then pbf.fix("xsph", "xsph", {c = var.xsph or 0.01}) end
end
pbf.fix("walls", "box", {})
local w = var.damping or 0.25
if w > 0 then
  pbf.fix("absorb_x", "damping", {from = {L - w, 0, 0}, to = {L, 0, 0}, rate = var.damping_rate})
  pbf.fix("absorb_y", "damping", {from = {0, L - w, 0}, to = {0, L, 0}, rate = var.damping_rate})
end

-- The still-water level: gauges between the sphere (r <= 0.15 m) and the damping zones.
local feet, labels = {}, {}
local r_g = math.min(0.42, L - w - 2 * s)
for k, deg in ipairs({10, 30, 45, 60, 80}) do
  feet[k] = {r_g * math.cos(math.rad(deg)), r_g * math.sin(math.rad(deg)), 0}
  labels[k] = string.format("g%02d", deg)
end
pbf.compute("level", "gauge", {points = feet, labels = labels})
pbf.fix("levels", "sample", {computes = {"level"}, interval = 0.01, file = out .. "/levels.csv"})

-- Mean of the gauges over steps in [t0, t1].
local acc = {sum = 0, n = 0, t0 = math.huge}
local function mean_level() local v = pbf.value("level"); local m = 0; for _, x in pairs(v) do m = m + x end; return m / #labels end
pbf.every("mean_level", 1, function(step, time)
  if time >= acc.t0 then acc.sum = acc.sum + mean_level(); acc.n = acc.n + 1 end
end)
local function measure(t_from, t_to)
  acc.sum, acc.n, acc.t0 = 0, 0, t_from
  pbf.run_until(t_to)
  acc.t0 = math.huge
  return acc.sum / acc.n
end

-- 1. settle
pbf.run_until(0.6 * t_settle)
local level0 = measure(0.6 * t_settle, t_settle)

-- The quarter sphere's volume below a flat surface with its centre a above it.
local function submerged(a)
  local c = math.max(0, math.min(2 * R, R - a))   -- the cap's height
  return math.pi * c * c * (3 * R - c) / 3 / 4
end
-- 2. hold: the centre where the sphere floats (the level it raises when half submerged) plus H0;
-- the fluid left out inside the sphere and its displacement balance (level_hold = level0).
local zc = level0 + H0
for _ = 1, 20 do zc = level0 + (submerged(0) - submerged(zc - level0)) / (L * L) + H0 end
local t_release = t_settle + t_hold
pbf.fix("sphere", "solid", {shape = "sphere", center = {0, 0, zc}, radius = R, mass = mass,
                            free_translation = {0, 0, 1}, free_rotation = {0, 0, 0}, hold = t_release})
pbf.compute("body", "body", {solid = "sphere"})
pbf.fix("track", "sample", {computes = {"body"}, interval = interval, file = out .. "/body.csv"})
local fz = {sum = 0, n = 0}
pbf.every("hold_force", 1, function(step, time)
  if time >= t_settle + 0.5 * t_hold and time <= t_release + 1e-9 then fz.sum = fz.sum + pbf.value("body").fz; fz.n = fz.n + 1 end
end)
pbf.run_until(t_settle + 0.5 * t_hold)
local level_hold = measure(t_settle + 0.5 * t_hold, t_release)
pbf.unfix("hold_force")
local a = zc - level_hold
local z_eq = level_hold + (submerged(0) - submerged(a)) / (L * L)
local F_hold, F_theory = fz.sum / fz.n, rho0 * g * submerged(a)
local meta = {
  solver = solver, h0_ratio = ratio, spacing = s, support = h / s, dt = dt, particles = pbf.count(),
  basin = L, depth = d, damping = w, rho0 = rho0, g = g, mass_quarter = mass, settle = t_settle, hold = t_hold,
  t_release = t_release, level0 = level0, level_hold = level_hold, z_center0 = zc, z_eq = z_eq, H0m = zc - z_eq,
  F_hold = F_hold, F_hold_theory = F_theory, weight = mass * g,
  stiffness_quarter = rho0 * g * math.pi * R * R / 4,
  iterations = solver == "pbf" and (var.iterations or 4) or 0, xsph = solver == "pbf" and (var.xsph or 0.01) or 0,
}
print(string.format("heave_decay: level %.5f m (settled), %.5f m (held sphere); centre %.5f m, equilibrium %.5f m, H0m %.5f m (nominal %.4g); hold force %.4g N (flat-surface buoyancy %.4g N, weight %.4g N)",
                    level0, level_hold, zc, z_eq, zc - z_eq, H0, F_hold, F_theory, mass * g))

-- 3. release
pbf.compute("err", "density_error")
pbf.thermo{every = math.max(1, math.floor(0.05 / dt)), columns = {"step", "time", "body.z", "body.vz", "body.fz", "err.compression"}}
pbf.run_until(t_release + t_end)
local f = assert(io.open(out .. "/meta.txt", "w"))
local keys = {}
for k in pairs(meta) do keys[#keys + 1] = k end
table.sort(keys)
for _, k in ipairs(keys) do f:write(k, " = ", tostring(meta[k]), "\n") end
f:close()
