# read_frame of a FIFO
# Expected: refused, ValueError: p.txt && not a regular file
import os
import pbfengine
os.mkfifo("p.txt")
pbfengine.read_frame("p.txt")
