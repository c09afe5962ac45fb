#!/usr/bin/env bash
# What a solid block costs a step of the dam break (share/benchmarks/body_cost.lua): none, at
# rest, moved by a motion, and a body the surge pushes, alternating, `repeats` times each
# (default 7); prints each run's loop time, the medians and their ratios to the analytic box
# alone (none).
#
#   share/benchmarks/body_cost.sh [PBFENGINE] [repeats] [particles]
here="$(cd "$(dirname "$0")" && pwd)"
exec "$here/variant_cost.sh" "$here/body_cost.lua" obstacle "none solid moving body" "$@"
