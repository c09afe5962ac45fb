-- bad_restarts.lua: writes a restart, good.restart, and damaged copies of it, read by the
-- one-line scripts of restart_errors.txt (docs/scripting.md, "Restart file errors").
pbf.kernel_radius(0.2)
pbf.timestep(0.01)
pbf.lattice{lo = {0, 0, 0}, hi = {0.5, 0.5, 0.5}, spacing = 0.1}
pbf.write_restart("good.restart")
local good = assert(io.open("good.restart", "rb")):read("a")
local function write(name, bytes)
  local f = assert(io.open(name, "wb"))
  f:write(bytes)
  f:close()
end
-- good with `bytes` in place of those from the 0-based offset `at` on
local function patch(at, bytes) return good:sub(1, at) .. bytes .. good:sub(at + #bytes + 1) end
write("text.restart", "This is a text file, not a restart file.\n")
write("short.restart", good:sub(1, 20))
write("trunc.restart", good:sub(1, -101))
write("corrupt.restart", patch(40, string.char(good:byte(41) ~ 0xff)))
write("bom.restart", patch(12, string.pack("<I4", 0x01020305)))
write("swapped.restart", patch(12, string.pack(">I4", 0x01020304)))   -- written big-endian
write("precision.restart", patch(16, string.pack("<I4", 2)))
write("version.restart", patch(8, string.pack("<I4", 3)))
