-- archimedes.lua: Archimedes' principle for a floating body (issue 33). A box a = 0.1 m high
-- and long, of density rel * 1000 kg/m^3, spans the width of a quasi-2D slab tank (0.4 m long,
-- W wide, water 0.16 m deep) and may only heave (free_translation {0, 0, 1}, no rotation).
-- It is held for `hold` seconds while the water settles around it, then released; it should
-- come to rest floating with a draft (the depth of its bottom below the water level) of
-- rel * a, and stay there.
--
--   pbfengine run share/validation/archimedes.lua [-v solver=pbf] [-v rel=0.5] [-v n=10] [-v csv=FILE]
--
-- Variables: solver ("pbf", the default, or "wcsph": share/lua/solvers.lua with its defaults),
-- rel (the body's density over the water's, default 0.5), n (lattice spacings per body
-- height: s = a / n, h = 2 s; default 10), width (the slab's width W in m, default 0.04;
-- rounded to whole spacings), t_end (simulated seconds, default 10), hold (seconds the body
-- is held, default 0.5), offset (m: the body starts this much above its expected draft,
-- default 0), dt (PBF's time step, default 0.4 h / sqrt(2 g H), H = 0.32 m the
-- tank's height; WCSPH's step is fix cfl's, at most this), interval (seconds between thermo
-- lines, default 0.01), csv (thermo CSV file, default none), out (frame directory, default
-- none).
--
-- The tank's length, width and water depth are whole numbers of spacings, so the lattice
-- fills them exactly (pbf.lattice places floor((hi - lo) / s) layers: a spacing that does not
-- divide the depth or the width leaves a layer out, and the water lower than the scene's
-- depth). The body starts at its expected draft (plus offset); the particles it covers, or nearer its
-- surface than its contact distance, are left out.
--
-- Columns: time, the body's centre z (b.z, m), its velocity (b.vz) and the fluid's force on
-- it (b.fz, N), the water level at twelve gauges, every 2 cm from 3 cm off the tank's ends to
-- 4 cm off the body (g.h1 ... g.h12, m: where the fluid fraction falls to 1/2; odd ones on the
-- x = 0 side, x = 0.03, 0.05, ..., 0.13 m, even ones mirrored) and the mean compression
-- (err.compression). The draft is the gauges' mean minus the body's bottom, b.z - a / 2; at
-- rest b.fz balances the body's weight m g.
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
package.path = here .. "../lua/?.lua;" .. package.path

local solver = var.solver or "pbf"
local rel = var.rel or 0.5                      -- body density / water density
local a = 0.1                                   -- body height and length (m)
local n = var.n or 10                           -- spacings per body height
local s = a / n                                 -- lattice spacing
local h = 2 * s                                 -- kernel radius
local g = 9.81
local rho0 = 1000
local function whole(x) return s * math.floor(x / s + 0.5) end  -- the nearest whole number of spacings
local L = whole(0.4)                            -- tank length (x)
local W = whole(var.width or 0.04)              -- slab width (y): the body spans it
local depth = whole(0.16)                       -- water depth at t = 0
local H = 2 * depth                             -- tank height
local t_end = var.t_end or 10
local hold = var.hold or 0.5
local dt = var.dt or 0.4 * h / math.sqrt(2 * g * H)

pbf.domain{lo = {0, 0, 0}, hi = {L, W, H}}
pbf.kernel_radius(h)
pbf.timestep(dt)
pbf.lattice{lo = {0, 0, 0}, hi = {L, W, depth}, spacing = s}

pbf.fix("gravity", "gravity", {})
if solver == "wcsph" then
  require("solvers").wcsph{}
elseif solver == "pbf" then
  pbf.fix("pbf", "pbf", {})
  pbf.fix("xsph", "xsph", {})
else
  error("archimedes: solver must be 'pbf' or 'wcsph', not " .. tostring(solver))
end
pbf.fix("walls", "box", {})
local z0 = depth - rel * a + (var.offset or 0)  -- the body's bottom at its expected draft
pbf.fix("float", "solid", {shape = "box", lo = {L / 2 - a / 2, 0, z0}, hi = {L / 2 + a / 2, W, z0 + a},
                           density = rel * rho0, hold = hold,
                           free_translation = {0, 0, 1}, free_rotation = {0, 0, 0}})
if var.out then pbf.fix("frames", "dump/text", {path = var.out .. "/frame_*.txt", interval = var.frame_interval or 0.05}) end

pbf.compute("b", "body", {solid = "float"})
-- the water level: gauges every 2 cm from 3 cm off each end wall to 4 cm off the body, six a side
local feet, columns = {}, {"step", "time", "b.z", "b.vz", "b.fz"}
for k = 0, 5 do
  for _, x in ipairs{0.03 + 0.02 * k, L - 0.03 - 0.02 * k} do
    feet[#feet + 1] = {x, W / 2, 0}
    columns[#columns + 1] = "g.h" .. #feet
  end
end
pbf.compute("g", "gauge", {points = feet})
pbf.compute("err", "density_error")
columns[#columns + 1] = "err.compression"
-- WCSPH steps are set by the sound speed c0 = 10 sqrt(2 g depth) (fix cfl), not by dt above
local dt_typical = solver == "wcsph" and 0.15 * h / (10 * math.sqrt(2 * g * depth)) or dt
pbf.thermo{every = math.max(1, math.floor((var.interval or 0.01) / dt_typical + 0.5)), csv = var.csv,
           columns = columns}

print(string.format("archimedes: %s, rel %.4g, %d lattice sites, spacing %.6g m, h %.6g m, dt %.4g s, tank %.4g x %.4g m, "
                    .. "depth %.4g m, body mass %.6g kg (weight %.6g N), expected draft %.6g m",
                    solver, rel, pbf.count(), s, h, dt, L, W, depth, rel * rho0 * a * a * W, rel * rho0 * a * a * W * g,
                    rel * a))
pbf.run_until(t_end)
