# read_vtu of 100 zero bytes
# Expected: refused, ValueError: f.vtu
import pbfengine
open("f.vtu", "wb").write(bytes(100))
pbfengine.read_vtu("f.vtu")
