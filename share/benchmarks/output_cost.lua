-- output_cost.lua: what output costs, measured on the dam break (vorticity and XSPH on).
-- The scene runs `steps` steps with no output (the baseline), then the same number again
-- with each dump style alone writing a frame every `every` steps; each style's line of the
-- timing table, divided by its frame count, is its cost per frame. Then a restart is
-- written (size per particle, time); with -v read=FILE the script only reads that restart
-- and reports the time, in a fresh process (share/benchmarks/output_cost.sh does both).
--
--   pbfengine run share/benchmarks/output_cost.lua [-v particles=30000] [-v out=/tmp/pbf-output-cost]
local out = var.out or "/tmp/pbf-output-cost"
if var.read then
  local r = pbf.read_restart(var.read)
  print(string.format("RESULT restart_read %d particles %.6f s", r.particles, r.seconds))
  return
end
local N = var.particles or 30000
local steps = var.steps or 100
local every = var.every or 10
local a, g = 0.1, 9.81
local layers = math.floor(N ^ (1 / 3) + 0.5)
local s = a / layers
local h = 2 * s
pbf.domain{lo = {0, 0, 0}, hi = {5 * a, layers // 2 * s, 4 * a}}
pbf.kernel_radius(h)
pbf.timestep(0.4 * h / math.sqrt(2 * g * 2 * a))
pbf.lattice{lo = {0, 0, 0}, hi = {a, layers // 2 * s, 2 * a}, spacing = s}
pbf.fix("gravity", "gravity", {acceleration = {0, 0, -g}})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.fix("vorticity", "vorticity", {})
pbf.fix("xsph", "xsph", {})
pbf.run(100)   -- let the column start to fall: frames of a moving fluid

local function row_seconds(label)
  for _, row in ipairs(pbf.timing().rows) do
    if row.label == label then return row.seconds end
  end
  error("no timing row " .. label)
end

pbf.run(steps)
local base = pbf.timing()
print(string.format("RESULT baseline %d particles %.6f s/step", pbf.count(), base.wall / steps))

local styles = {
  {"dump/text", {path = out .. "/text/frame_*.txt"}},
  {"dump/text", {path = out .. "/text-all/frame_*.txt", fields = {"id", "position", "velocity", "density", "speed"}},
   "dump/text with density"},
  {"dump/vtk", {path = out .. "/vtk/frame_*.vtu", fields = {"id", "velocity"}}, "dump/vtk id+velocity"},
  {"dump/vtk", {path = out .. "/vtk-density/frame_*.vtu"}, "dump/vtk (default fields, with density)"},
  {"dump/image", {path = out .. "/image/image_*.png"}},
  {"dump/movie", {path = out .. "/movie.mp4"}},
}
for _, entry in ipairs(styles) do
  local style, params, name = entry[1], entry[2], entry[3] or entry[1]
  params.every = every
  pbf.fix("out", style, params)
  pbf.run(steps)
  local frames = steps // every   -- in the run; frame 0 is written by init, outside the table
  local seconds = row_seconds("out (" .. style .. ")")
  print(string.format("RESULT %s %.6f s/frame (%d frames)", name, seconds / frames, frames))
  pbf.unfix("out")
end

local r = pbf.write_restart(out .. "/bench.restart")
print(string.format("RESULT restart_write %d particles %d bytes %.1f bytes/particle %.6f s",
                    r.particles, r.bytes, r.bytes / r.particles, r.seconds))
