# read_frame of /dev/zero
# Expected: refused, ValueError: /dev/zero && not a regular file
import pbfengine
pbfengine.read_frame("/dev/zero")
