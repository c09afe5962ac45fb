-- solvers.lua: the weakly compressible SPH pipeline the scenarios share when run with
-- -v solver=wcsph (their PBF pipelines differ by scenario and stay in them):
--   leapfrog (kick-drift-kick), wcsph (summed density, Tait pressure, pressure force),
--   sph_viscosity (Monaghan's artificial viscosity), cfl (time-step control)
-- Gravity and walls are the scenario's, as for PBF. Options, each nil for the style's
-- default: alpha, eos, density, diffusion (delta-SPH, with density = "continuity"),
-- negative_pressure (true: a stretched surface pulls back instead of being clamped), sound_speed,
-- courant, align (s: steps end on multiples of it), fixed_dt (true: no cfl; the script's time
-- step is used as it is).
local solvers = {}
local flag = require("flag")

function solvers.wcsph(opts)
  opts = opts or {}
  pbf.fix("integrator", "leapfrog", {})
  pbf.fix("wcsph", "wcsph", {eos = opts.eos, density = opts.density, sound_speed = opts.sound_speed,
                             diffusion = opts.diffusion, negative_pressure = flag(opts.negative_pressure, nil, "negative_pressure")})
  pbf.fix("viscosity", "sph_viscosity", {alpha = opts.alpha})
  local fixed = flag(opts.fixed_dt, false, "fixed_dt")
  if not fixed then pbf.fix("cfl", "cfl", {courant = opts.courant, align = opts.align}) end
end

-- The divergence-free SPH pipeline of -v solver=dfsph: dfsph (its two solves and its
-- integrator), sph_viscosity (Laplacian, nu = 1e-3 m^2/s: numerical, it damps the settling of
-- the lattice a scene starts from, which no solver here survives undamped; docs/physics.md,
-- "DFSPH") and cfl (courant 0.4 on h / |v|max; the script's step is the largest). Options,
-- each nil for the default: error, divergence_error, max_iterations (of both solves), nu (0:
-- no viscosity), courant, align, fixed_dt.
function solvers.dfsph(opts)
  opts = opts or {}
  pbf.fix("dfsph", "dfsph", {error = opts.error, divergence_error = opts.divergence_error,
                             max_iterations = opts.max_iterations, divergence_max_iterations = opts.max_iterations})
  local nu = opts.nu or 1e-3
  if nu > 0 then pbf.fix("viscosity", "sph_viscosity", {kind = "laplacian", nu = nu}) end
  local fixed = flag(opts.fixed_dt, false, "fixed_dt")
  if not fixed then pbf.fix("cfl", "cfl", {courant = opts.courant or 0.4, align = opts.align}) end
end

return solvers
