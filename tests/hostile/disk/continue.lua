-- continue.lua: reads a restart (-v file=PATH) and runs one more step: the restart is valid.
pbf.read_restart(var.file)
pbf.fix("gravity", "gravity", {})
pbf.fix("pbf", "pbf", {})
pbf.fix("walls", "box", {})
pbf.run(1)
