-- floating.lua: bodies dropped into a tank of water, rocking and settling. A tank 0.6 m long,
-- 0.4 m wide and 0.45 m high holds water 0.2 m deep; after 0.3 s of settling four bodies are
-- released from the air above it: a plank of pine (500 kg/m^3, 0.16 x 0.08 x 0.05 m), tilted,
-- which floats with half its height under; a cube of oak (800 kg/m^3, 6 cm), which floats deep;
-- a ball of cork-filled plastic (600 kg/m^3, 4.5 cm radius), rolled in from the side; and a
-- ball of stone (2,500 kg/m^3, 3 cm radius), which sinks and rests on the floor. Each is a
-- `solid` with a density: the fluid moves it and it moves the fluid (docs/user-guide.md#bodies).
-- The water settles in about 3 s; the bodies keep rocking on its waves a little longer.
-- With -v joints=true two more hang on joints: a buoy on a slider (a guide tilted 1 in 5 from
-- the vertical) that slides down into the water and floats on it, and a heavy ball on a ball
-- joint 0.11 m from it, which swings down through the surface and back.
--
--   pbfengine run scenarios/floating.lua [-v particles=30000] [-v t_end=4] [-v out=out]
--   pbfengine run scenarios/floating.lua -v images=0.02        (pictures, out/image_*.png)
--   pbfengine run scenarios/floating.lua -v vtk=0.02           (ParaView: out/vtk/frame.pvd)
--
-- Variables: particles (about how many, default 30000), t_end (simulated seconds, default 4),
-- out (output directory, default "out"; "" for none), solver ("pbf", the default, or
-- "wcsph"), joints (default false); images, movie and vtk as in every scenario
-- (share/lua/outputs.lua). Writes OUT/thermo.csv: each body's height z (m) and its turn about
-- x and y (degrees).
local here = debug.getinfo(1, "S").source:match("^@(.*[/\\])") or "./"
package.path = here .. "../share/lua/?.lua;" .. package.path
local N = var.particles or 30000
local t_end = var.t_end or 4
local out = var.out or "out"
local g = 9.81
local L, W, H, depth = 0.6, 0.4, 0.45, 0.2

local s = (L * W * depth / N) ^ (1 / 3)      -- lattice spacing
s = W / math.floor(W / s + 0.5)              -- a whole number of layers across the tank
local h = 2 * s
local wcsph = (var.solver or "pbf") == "wcsph"

pbf.domain{lo = {0, 0, 0}, hi = {L, W, H}}
pbf.kernel_radius(h)
-- PBF: 0.4 h per step at the speed of a fall from 0.25 m; WCSPH: the CFL bound chooses.
pbf.timestep(0.4 * h / math.sqrt(2 * g * 0.25))
local n = pbf.lattice{lo = {0, 0, 0}, hi = {L, W, depth}, spacing = s}
print(string.format("floating: %d particles, spacing %.4g m, h %.4g m", n, s, h))

pbf.fix("gravity", "gravity", {acceleration = {0, 0, -g}})
if wcsph then
  require("solvers").wcsph{}
else
  pbf.fix("pbf", "pbf", {})
  pbf.fix("vorticity", "vorticity", {})
  pbf.fix("xsph", "xsph", {})
end
pbf.fix("walls", "box", {})

local hold = 0.3
-- (A box is given about the origin, turned there, then moved into place: `rotate` turns about
-- the origin.)
pbf.fix("plank", "solid", {shape = "box", lo = {-0.08, -0.04, -0.025}, hi = {0.08, 0.04, 0.025}, rotate = {0, 12, 8},
                           translate = {0.16, 0.12, 0.32}, density = 500, hold = hold})
pbf.fix("cube", "solid", {shape = "box", lo = {-0.03, -0.03, -0.03}, hi = {0.03, 0.03, 0.03}, rotate = {20, 0, 0},
                          translate = {0.4, 0.25, 0.3}, density = 800, hold = hold})
pbf.fix("ball", "solid", {shape = "sphere", center = {0.45, 0.1, 0.3}, radius = 0.045, density = 600, hold = hold,
                          velocity = {-0.3, 0, 0}})
pbf.fix("stone", "solid", {shape = "sphere", center = {0.2, 0.3, 0.3}, radius = 0.03, density = 2500, hold = hold})
local bodies = {"plank", "cube", "ball", "stone"}
if require("flag")(var.joints, false, "joints") then
  pbf.fix("buoy", "solid", {shape = "sphere", center = {0.08, 0.3, 0.28}, radius = 0.035, density = 400, hold = hold,
                            slider = {0.2, 0, -1}})
  pbf.fix("lamp", "solid", {shape = "sphere", center = {0.5, 0.34, 0.3}, radius = 0.03, density = 1500, hold = hold,
                            ball_joint = {0.39, 0.34, 0.3}})
  bodies[#bodies + 1], bodies[#bodies + 2] = "buoy", "lamp"
end

require("outputs").add(out, {color = "speed", min = 0, max = 1, direction = {0.6, 1.6, -1.2}})
local columns = {"step", "time"}
for _, body in ipairs(bodies) do
  pbf.compute(body, "body", {solid = body})
  for _, c in ipairs{"z", "rx", "ry"} do columns[#columns + 1] = body .. "." .. c end
end
pbf.thermo{every = math.max(1, math.floor(0.02 / pbf.timestep())), columns = columns,
           csv = out ~= "" and out .. "/thermo.csv" or nil}
pbf.run_until(t_end)
