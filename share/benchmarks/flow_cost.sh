#!/usr/bin/env bash
# What an emitter and a sink add to a step: the dam break of compare_step.sh (33,750
# particles, 75 steps) without and with a small emitter and a sink (share/benchmarks/flow_cost.lua,
# -v flow=0 and 1), alternating, `repeats` times each (default 7); prints each run's loop
# time, the medians and their ratio (with / without).
#
#   share/benchmarks/flow_cost.sh [PBFENGINE] [repeats] [particles]
here="$(cd "$(dirname "$0")" && pwd)"
exec "$here/variant_cost.sh" "$here/flow_cost.lua" flow "0 1" "$@"
