#!/usr/bin/env bash
# Whether two gcodec binaries give the same bytes: `run` (JSONL and CSV)
# and `lower` (listing and JSON) of every .mpf under the given folders, on
# the built-in machine and on two profiles of profiles/, stdout and stderr
# compared apart. For changes meant to change no output (speed work).
#
# Usage: scripts/measure/compare-outputs.sh OLD NEW FOLDER...
#   e.g. scripts/measure/compare-outputs.sh old/gcodec new/gcodec examples tests ../shared/corpus
# Prints each run that differs and the counts; exit status 1 if any does.
set -euo pipefail
[ $# -ge 3 ] || { sed -n '2,9p' "$0" >&2; exit 2; }
old=$1 new=$2
shift 2
profiles=$(cd "$(dirname "$0")/../../profiles" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
same=0 different=0
while IFS= read -r -d '' program; do
    for machine in "" "--profile $profiles/lathe_828d.toml" "--profile $profiles/mill_5axis.toml"; do
        for command in "run" "run --format csv" "lower" "lower --format json"; do
            for side in old new; do
                # shellcheck disable=SC2086 # the command and machine are words
                timeout 60 "${!side}" $command $machine "$program" >"$out/$side.out" 2>"$out/$side.err" || true
            done
            if cmp -s "$out/old.out" "$out/new.out" && cmp -s "$out/old.err" "$out/new.err"; then
                same=$((same + 1))
            else
                different=$((different + 1))
                echo "differs: $command $machine $program"
            fi
        done
    done
done < <(find "$@" -iname '*.mpf' -not -path '*/target/*' -print0 | sort -z)
echo "same $same, different $different"
[ "$different" -eq 0 ]
