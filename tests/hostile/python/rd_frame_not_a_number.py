# read_frame of a frame with a word on line 3
# Expected: refused, ValueError: f.txt:3: && 'x'
import pbfengine
open("f.txt", "w").write("2\n1 2 3 4 5 6\n1 2 x 4 5 6\n")
pbfengine.read_frame("f.txt")
