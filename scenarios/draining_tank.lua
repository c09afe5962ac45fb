-- draining_tank.lua: a tank draining through an orifice in its floor. A tank 0.2 m x 0.2 m in
-- plan holds water 0.2 m deep on a floor that is a solid slab 2 cm thick (a mesh the script
-- writes: a square plate with a square hole, the orifice, `orifice` m across, in its middle).
-- The water runs out through the hole as a jet, falls 4 cm and leaves the run through the
-- domain's open bottom face (the box fix with `open = {"z-"}`). Torricelli's law with a
-- discharge coefficient C_d, dh/dt = -C_d (a/A) sqrt(2 g h) (h the level over the slab's top
-- face, a the orifice's area, A the tank's), says that sqrt(h) falls linearly in time; the
-- gauges (`level.*`, at four points 4 cm from the tank's walls, away from the orifice) give
-- h(t), and the flow compute (`out`) what left. share/validation/draining_tank.py runs it and
-- fits C_d (docs/validation/draining_tank.md).
--
--   pbfengine run scenarios/draining_tank.lua [-v t_end=2.5] [-v out=out] [-v solver=pbf|wcsph]
--
-- Variables: t_end (simulated seconds, default 2.5), s (particle spacing, default 0.01 m),
-- orifice (the hole's side, default 0.06 m), depth (the water's starting depth, default 0.2 m),
-- out (frame directory, default "out"; "" for none), interval (seconds between frames, default
-- 0.02), csv (the thermo CSV, default out/thermo.csv), solver ("pbf", default, or "wcsph";
-- share/lua/solvers.lua). Pictures, a movie and ParaView frames with -v images=T,
-- -v movie=PATH, -v vtk=T (share/lua/outputs.lua); restarts every restart_interval seconds
-- (default 0.5; 0 for none), -v restart=FILE continues from one (the slab's mesh is written
-- to out/orifice_plate.obj, or to a temporary file with out="").
package.path = (debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./") .. "../share/lua/?.lua;" .. package.path
local solver = var.solver or "pbf"
assert(solver == "pbf" or solver == "wcsph", "solver must be pbf or wcsph, got " .. tostring(solver))
local t_end = var.t_end or 2.5
local out = var.out or "out"
local s = var.s or 0.01
local b = var.orifice or 0.06
local depth = var.depth or 0.2
local L = 0.2                      -- the tank's side (plan L x L)
local z0, z1 = 0.04, 0.06          -- the slab: from z0 to z1; below it the jet falls to the open floor
local H = z1 + depth + 0.06        -- the domain's top
local g = 9.81
assert(b > 0 and b < L - 0.04, "orifice must be in (0, " .. (L - 0.04) .. ") m, got " .. tostring(b))

-- The slab: a plate wider than the tank (so that it meets the box's walls with no gap) with a
-- square hole of side b at the tank's centre, as a closed triangle mesh (genus one).
local function write_plate(path)
  local c, m = L / 2, 0.02
  local outer = {{-m, -m}, {L + m, -m}, {L + m, L + m}, {-m, L + m}}
  local inner = {{c - b / 2, c - b / 2}, {c + b / 2, c - b / 2}, {c + b / 2, c + b / 2}, {c - b / 2, c + b / 2}}
  local f = assert(io.open(path, "w"))
  f:write("# a plate with a square hole: scenarios/draining_tank.lua\n")
  -- vertices: outer bottom 1-4, outer top 5-8, inner bottom 9-12, inner top 13-16
  for _, ring in ipairs({outer, inner}) do
    for _, z in ipairs({z0, z1}) do
      for _, p in ipairs(ring) do f:write(string.format("v %.9g %.9g %.9g\n", p[1], p[2], z)) end
    end
  end
  local function quad(a, b_, c_, d) f:write(string.format("f %d %d %d\nf %d %d %d\n", a, b_, c_, a, c_, d)) end
  for k = 0, 3 do
    local k1 = (k + 1) % 4
    quad(5 + k, 5 + k1, 13 + k1, 13 + k)    -- top face (normal +z)
    quad(1 + k, 9 + k, 9 + k1, 1 + k1)      -- bottom face (normal -z)
    quad(1 + k, 1 + k1, 5 + k1, 5 + k)      -- outer side (normal outward)
    quad(9 + k, 13 + k, 13 + k1, 9 + k1)    -- the hole's side (normal into the hole)
  end
  f:close()
end

local scene = pbf.scene(function()
  pbf.domain{lo = {0, 0, 0}, hi = {L, L, H}}
  pbf.kernel_radius(2 * s)
  pbf.timestep(0.4 * 2 * s / math.sqrt(2 * g * (z1 + depth)))   -- 0.4 h per step at the speed of a fall from the top
  pbf.lattice{lo = {0, 0, z1}, hi = {L, L, z1 + depth}, spacing = s}
end)

local plate
if out ~= "" then plate = out .. "/orifice_plate.obj" else
  local tmp = os.tmpname(); os.remove(tmp); plate = tmp .. ".obj"
end
if out ~= "" then os.execute("mkdir -p '" .. out .. "'") end
write_plate(plate)

pbf.fix("gravity", "gravity", {acceleration = {0, 0, -g}})
if solver == "wcsph" then
  require("solvers").wcsph{sound_speed = 10 * math.sqrt(2 * g * (z1 + depth)), density = "continuity",
                           diffusion = 0.1}
else
  pbf.fix("pbf", "pbf", {iterations = 4})
  pbf.fix("xsph", "xsph", {c = 0.01})
end
pbf.fix("walls", "box", {open = {"z-"}})
pbf.fix("plate", "solid", {file = plate})

require("outputs").add(out, {color = "speed", min = 0, max = 2, direction = {0.6, 1.6, -0.9}, zoom = 1.2})
require("outputs").frames(out, 0.5)

pbf.compute("n", "count")
pbf.compute("out", "flow", {fix = "walls"})
local d = 0.04   -- the gauges' distance from the walls
pbf.compute("level", "gauge", {points = {{d, d, z1}, {L - d, d, z1}, {d, L - d, z1}, {L - d, L - d, z1}},
                               labels = {"a", "b", "c", "d"}})
pbf.compute("err", "density_error")
pbf.thermo{every = math.max(1, math.floor(0.02 / pbf.timestep() + 0.5)),
           csv = var.csv or (out ~= "" and out .. "/thermo.csv" or nil),
           columns = {"step", "time", "n", "out.count", "out.mass", "level.a", "level.b", "level.c", "level.d",
                      "err.avg"}}

print(string.format("draining_tank (%s): %d particles %.3g m deep over a %.3g m square orifice (a/A = %.4g), to t = %g s",
                    solver, pbf.count(), depth, b, (b / L) ^ 2, t_end))
if scene.restart then print("continuing from " .. scene.restart) end
pbf.run_until(t_end)
