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

return solvers
