# read_frame of a missing file
# Expected: refused, FileNotFoundError: nope.txt
import pbfengine
pbfengine.read_frame("nope.txt")
