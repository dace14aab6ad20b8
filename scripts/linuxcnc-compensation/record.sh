#!/usr/bin/env bash
# Records LinuxCNC's compensated paths: runs rs274, LinuxCNC's standalone
# interpreter (Debian's linuxcnc-uspace), on every fixture program
# tests/fixtures/compensation/linuxcnc/NAME.ngc with that folder's tool
# table and writes the canonical calls it prints, unedited, to
# NAME.rs274.txt beside it. CI does not install LinuxCNC: the recordings
# are checked in, and gcodec-driver's linuxcnc_compensation test reads them.
#
# Usage: scripts/linuxcnc-compensation/record.sh [FIXTURE_DIR]
# Exit codes: 0 recorded, 1 rs274 rejected a program, 2 rs274 missing or
# the folder or its tool table not found.
set -euo pipefail

if ! command -v rs274 >/dev/null 2>&1; then
    echo "record.sh: rs274 not found on PATH; install LinuxCNC's interpreter (apt-get install linuxcnc-uspace)" >&2
    exit 2
fi

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
dir=${1:-"$repo/tests/fixtures/compensation/linuxcnc"}
table="$dir/tools.tbl"

if [[ ! -f "$table" ]]; then
    echo "record.sh: no tool table at $table" >&2
    exit 2
fi

shopt -s nullglob
programs=("$dir"/*.ngc)
if ((${#programs[@]} == 0)); then
    echo "record.sh: no .ngc programs in $dir" >&2
    exit 2
fi

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

status=0
for program in "${programs[@]}"; do
    name=$(basename "$program" .ngc)
    # -g runs the program to its end without stopping at M0/M1; rs274
    # prints the calls on stdout, "executing" and its errors on stderr,
    # and exits 1 when the interpreter rejects a block. A recording is
    # replaced only by a complete one.
    if rs274 -t "$table" -g "$program" >"$scratch/$name.txt" 2>"$scratch/$name.err"; then
        mv "$scratch/$name.txt" "$dir/$name.rs274.txt"
        echo "recorded $name.rs274.txt"
    else
        echo "record.sh: rs274 rejected $name.ngc:" >&2
        grep -v '^executing$' "$scratch/$name.err" >&2 || true
        status=1
    fi
done
exit "$status"
