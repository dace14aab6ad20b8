#!/usr/bin/env bash
# The phases of one streamed run, from the scheduler's view: each gcodec
# thread's first and last moment on a CPU, in ms after the main thread's
# first. The line-table helper, pass 1's two skim threads, then pass 2's
# coordinator and workers beside the main thread, which runs the program.
#
# Usage: scripts/measure/stream-phases.sh GCODEC PROGRAM [GCODEC ARGS...]
#   e.g. scripts/measure/stream-phases.sh target/release/gcodec flood_1m.mpf run
# Needs `perf sched` (linux-perf) and the right to record scheduler events.
set -euo pipefail
[ $# -ge 2 ] || { sed -n '2,9p' "$0" >&2; exit 2; }
bin=$1 program=$2
shift 2
args=("$@")
[ ${#args[@]} -gt 0 ] || args=(run)
data=$(mktemp)
trap 'rm -f "$data"' EXIT
perf sched record -q -o "$data" "$bin" "${args[@]}" "$program" >/dev/null 2>&1
name=$(basename "$bin" | cut -c1-15)
perf sched timehist -i "$data" 2>/dev/null |
    awk -v name="$name" '$3 ~ "^" name "\\[" {print $1, $3}' |
    awk '
    NR == 1 { main = $2 }
    { if (!($2 in first)) { first[$2] = $1; order[n++] = $2 } last[$2] = $1 }
    END {
        t0 = first[main]
        for (i = 0; i < n; i++) {
            id = order[i]
            printf "%-28s %7.1f .. %7.1f ms\n", id, (first[id] - t0) * 1000, (last[id] - t0) * 1000
        }
    }'
