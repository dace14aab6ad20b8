#!/usr/bin/env bash
# Benchmarks gcodec against its closest peer, CEAD-group's
# nc-gcode-interpreter 0.2.8 (issue 20): generates the seven programs of
# the issue's table, runs both sides interleaved and prints a markdown
# table of median wall times and peak RSS, then the peer's example
# programs, one process each, in total.
#
# Usage: scripts/bench-peer/run.sh [--build-peer [DIR]] [--peer-dir DIR]
#   --build-peer [DIR]  download the peer's sdist with pip into DIR
#                       (default /work/peer, outside the repository),
#                       unpack it and build its release binary there,
#                       with its own CARGO_TARGET_DIR inside DIR
#   --peer-dir DIR      use the peer already built in DIR
# Environment:
#   GCODEC=PATH         use this gcodec binary instead of building one
#   ROUNDS=N            interleaved rounds per program (default 3)
#   EXAMPLES=DIR        the peer's example programs
#                       (default /work/shared/corpus/peer-cead)
#   PEER_LIMIT=N        the peer's loop iteration limit (default 2000000)
# Exit codes: 0 measured, 2 usage error, peer or gcodec missing or not
# built, or a program of the table rejected by either side.
set -euo pipefail

peer_version=0.2.8
peer_dir=/work/peer
build_peer=0
while (($#)); do
    case $1 in
    --build-peer)
        build_peer=1
        if (($# > 1)) && [[ $2 != --* ]]; then
            peer_dir=$2
            shift
        fi
        ;;
    --peer-dir)
        (($# > 1)) || { echo "run.sh: --peer-dir needs a folder" >&2; exit 2; }
        peer_dir=$2
        shift
        ;;
    -h | --help)
        sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'
        exit 0
        ;;
    *)
        echo "run.sh: unknown argument '$1' (see --help)" >&2
        exit 2
        ;;
    esac
    shift
done

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
rounds=${ROUNDS:-3}
examples=${EXAMPLES:-/work/shared/corpus/peer-cead}
peer_limit=${PEER_LIMIT:-2000000}
peer_dir=$(realpath -m "$peer_dir")
case $peer_dir/ in
"$repo"/*)
    echo "run.sh: the peer's folder must be outside the repository ($peer_dir)" >&2
    exit 2
    ;;
esac
((build_peer)) && mkdir -p "$peer_dir"
peer_src=$peer_dir/nc_gcode_interpreter-$peer_version
peer=$peer_dir/target/release/nc-gcode-interpreter

if ((build_peer)); then
    echo "building the peer $peer_version in $peer_dir" >&2
    # pip is the sdist's ordinary client; --no-binary gives the source,
    # --ignore-requires-python because only its Rust CLI is built.
    python3 -m pip download "nc-gcode-interpreter==$peer_version" --no-binary :all: \
        --no-deps --ignore-requires-python -d "$peer_dir" >&2
    tar -xzf "$peer_dir/nc_gcode_interpreter-$peer_version.tar.gz" -C "$peer_dir"
    (cd "$peer_src" && CARGO_TARGET_DIR=$peer_dir/target CARGO_INCREMENTAL=0 \
        cargo build --release --locked --bin nc-gcode-interpreter >&2)
fi
if [[ ! -x $peer ]]; then
    echo "run.sh: no peer binary at $peer; build it with: $0 --build-peer $peer_dir" >&2
    exit 2
fi

if [[ -n ${GCODEC:-} ]]; then
    gcodec=$GCODEC
else
    # The binary as shipped: static on GNU/Linux (scripts/build-release.sh).
    gcodec=$(CARGO_INCREMENTAL=0 "$repo/scripts/build-release.sh")
fi
if [[ ! -x $gcodec ]]; then
    echo "run.sh: no gcodec binary at $gcodec" >&2
    exit 2
fi

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
programs_dir=$scratch/programs
python3 "$here/generate.py" "$programs_dir"
programs=(flood_200k flood_1m numbered_1m if_1m while_1m while_nomotion_1m gotob_1m)

# One measured process: appends "program side round wall_s rss_kb status"
# to the results. The peer writes FILE.csv beside its input; that file is
# removed after each run so the disk holds one at a time.
results=$scratch/results.tsv
measure() {
    local program=$1 side=$2 round=$3 file=$programs_dir/$1.mpf status=0
    local timing=$scratch/time.txt start end
    # Wall time from the shell's microsecond clock (`%e` counts in steps
    # of 10 ms, a seventh of a 200,000-line run); /usr/bin/time gives the
    # peak RSS. Its own start is inside both sides' times alike.
    start=$EPOCHREALTIME
    case $side in
    gcodec_jsonl) /usr/bin/time -f "%M" -o "$timing" "$gcodec" run "$file" >/dev/null 2>"$scratch/err" || status=$? ;;
    gcodec_csv) /usr/bin/time -f "%M" -o "$timing" "$gcodec" run --format csv "$file" >/dev/null 2>"$scratch/err" || status=$? ;;
    peer) /usr/bin/time -f "%M" -o "$timing" "$peer" -l "$peer_limit" "$file" >/dev/null 2>"$scratch/err" || status=$? ;;
    esac
    end=$EPOCHREALTIME
    rm -f "$programs_dir/$program.csv"
    if ((status != 0)); then
        echo "run.sh: $side exited $status on $program.mpf:" >&2
        head -5 "$scratch/err" >&2
    fi
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$program" "$side" "$round" \
        "$(python3 -c "print(round($end - $start, 4))")" "$(tail -1 "$timing")" "$status" >>"$results"
}

load_before=$(cut -d' ' -f1-3 /proc/loadavg)
for ((round = 1; round <= rounds; round++)); do
    for program in "${programs[@]}"; do
        echo "round $round/$rounds: $program" >&2
        measure "$program" gcodec_jsonl "$round"
        measure "$program" peer "$round"
        measure "$program" gcodec_csv "$round"
    done
done

# The peer's examples, copied because the peer writes its CSV beside the
# input. Each runs once on both sides first; only those both exit 0 on
# are timed, as one loop of processes per side, the sides alternating.
# gcodec runs each on the machine it needs (gcodec.toml beside this
# script: rotary axes, tool management) and past `M0`, as the peer does.
examples_dir=$scratch/examples
gcodec_example=("$gcodec" run --config "$here/gcodec.toml" --no-stop)
mkdir -p "$examples_dir"
cp "$examples"/*.mpf "$examples_dir"/
# The first diagnostic that says why: gcodec reports a run stopped at a
# block with errors (alarm 12080) beside the error that caused it.
gcodec_reason() {
    awk '/^gcodec::/ { code = $1; next }
        /×/ && code != "" {
            sub(/^[[:space:]]*×[[:space:]]*/, "")
            line = code ": " $0
            if (code != "gcodec::run::block_with_errors") { print line; found = 1; exit }
            if (first == "") first = line
        }
        END { if (!found && first != "") print first }' "$1"
}
kept=()
excluded=$scratch/excluded.tsv
: >"$excluded"
for file in "$examples_dir"/*.mpf; do
    name=$(basename "$file")
    g=0 p=0
    "${gcodec_example[@]}" "$file" >/dev/null 2>"$scratch/gerr" || g=$?
    "$peer" -l "$peer_limit" "$file" >/dev/null 2>"$scratch/perr" || p=$?
    if ((g == 0 && p == 0)); then
        kept+=("$file")
    else
        reason=""
        ((g == 0)) || reason="gcodec exit $g: $(gcodec_reason "$scratch/gerr" | cut -c1-120)"
        ((p == 0)) || reason="${reason:+$reason; }peer exit $p: $(grep -m1 . "$scratch/perr" | cut -c1-100)"
        printf '%s\t%s\n' "$name" "$reason" >>"$excluded"
    fi
done
examples_tsv=$scratch/examples.tsv
: >"$examples_tsv"
run_all() {
    local side=$1 file
    for file in "${kept[@]}"; do
        if [[ $side == gcodec_jsonl ]]; then
            "${gcodec_example[@]}" "$file" >/dev/null 2>&1
        else
            "$peer" -l "$peer_limit" "$file" >/dev/null 2>&1
        fi
    done
}
for ((round = 1; round <= rounds; round++)); do
    for side in gcodec_jsonl peer; do
        start=$EPOCHREALTIME
        run_all "$side"
        end=$EPOCHREALTIME
        printf '%s\t%s\t%s\n' "$side" "$round" "$(python3 -c "print($end - $start)")" >>"$examples_tsv"
    done
done
load_after=$(cut -d' ' -f1-3 /proc/loadavg)

echo
# A given binary may not be the checkout's build: say which it is.
built="built from $(git -C "$repo" rev-parse --short HEAD)"
[[ -n ${GCODEC:-} ]] && built="$gcodec, the checkout at $(git -C "$repo" rev-parse --short HEAD)"
echo "$("$gcodec" --version 2>/dev/null | head -1) ($built), peer $("$peer" --version | head -1)"
echo "$(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, $rounds rounds, load average (1/5/15 min) $load_before before, $load_after after"
echo
python3 "$here/table.py" "$results" "$examples_tsv" "${#kept[@]}" "$excluded"
if awk -F'\t' '$6 != 0 { bad = 1 } END { exit !bad }' "$results"; then
    echo "run.sh: a program of the table was rejected (see above)" >&2
    exit 2
fi
