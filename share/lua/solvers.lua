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

-- A -v value arrives as a string: "true" and "false" mean the booleans.
local function boolean(value)
  if value == "true" then return true elseif value == "false" then return false end
  return value
end

function solvers.wcsph(opts)
  opts = opts or {}
  pbf.fix("integrator", "leapfrog", {})
  pbf.fix("wcsph", "wcsph", {eos = opts.eos, density = opts.density, sound_speed = opts.sound_speed,
                             diffusion = opts.diffusion, negative_pressure = boolean(opts.negative_pressure)})
  pbf.fix("viscosity", "sph_viscosity", {alpha = opts.alpha})
  local fixed = opts.fixed_dt ~= nil and opts.fixed_dt ~= false and opts.fixed_dt ~= 0 and opts.fixed_dt ~= "false"
  if not fixed then pbf.fix("cfl", "cfl", {courant = opts.courant, align = opts.align}) end
end

return solvers
