#!/usr/bin/env bash
# Paired whole-process timings of two gcodec binaries: the old and the new
# run in turn, ROUNDS times, on one program; prints the medians of wall
# time and of CPU time (user + system), in seconds.
#
# Usage: scripts/measure/paired-timing.sh OLD NEW ROUNDS PROGRAM [GCODEC ARGS...]
#   e.g. scripts/measure/paired-timing.sh old/gcodec new/gcodec 15 flood_1m.mpf run --format csv
# Needs GNU time (/usr/bin/time). Output goes to /dev/null.
set -euo pipefail
[ $# -ge 4 ] || { sed -n '2,8p' "$0" >&2; exit 2; }
old=$1 new=$2 rounds=$3 program=$4
shift 4
args=("$@")
[ ${#args[@]} -gt 0 ] || args=(run)
times=$(mktemp)
trap 'rm -f "$times" "$times.one"' EXIT
for ((round = 0; round < rounds; round++)); do
    for side in old new; do
        bin=${!side}
        /usr/bin/time -o "$times.one" -f "%e %U %S" "$bin" "${args[@]}" "$program" >/dev/null 2>&1 || true
        read -r wall user system <"$times.one"
        echo "$side $wall $(echo "$user + $system" | bc)" >>"$times"
    done
done
median() { sort -n | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
for side in old new; do
    wall=$(awk -v s=$side '$1 == s {print $2}' "$times" | median)
    cpu=$(awk -v s=$side '$1 == s {print $3}' "$times" | median)
    printf '%s: wall %s s, CPU %s s\n' "$side" "$wall" "$cpu"
done
