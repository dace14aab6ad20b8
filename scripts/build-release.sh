#!/usr/bin/env bash
# Builds the `gcodec` executable as it is shipped: the release profile and,
# on GNU/Linux, linked statically at a fixed address.
#
# A static executable has no dynamic loader to run and no shared libraries
# to map, relocate and fault in: a short program's whole run takes about
# 1.7 ms instead of 2.8 ms, and the peer's 25 example programs run in
# about two thirds of the time (docs/performance.md, "Issue 20: a
# statically linked release binary"). `cargo build --release` cannot ask
# for this: `-C target-feature=+crt-static` in RUSTFLAGS or
# `.cargo/config.toml` reaches the proc-macro crates too, which cannot be
# built static. `cargo rustc` gives the flags to the `gcodec` crate alone,
# and with the release profile's fat LTO that crate generates all the
# code, so the dependencies' builds are shared with `cargo build
# --release`.
#
# Usage: scripts/build-release.sh [CARGO OPTION]...   (e.g. --locked)
# Prints the executable's path last: target/release/gcodec, or under
# CARGO_TARGET_DIR. Elsewhere than GNU/Linux it is the plain release build.
set -euo pipefail

cd "$(dirname "$0")/.."
host=$(rustc -vV | sed -n 's/^host: //p')
case $host in
*-linux-gnu)
    cargo rustc --release -p gcodec-cli --bin gcodec "$@" -- \
        -C target-feature=+crt-static -C relocation-model=static >&2
    ;;
*)
    cargo build --release -p gcodec-cli "$@" >&2
    ;;
esac
echo "${CARGO_TARGET_DIR:-$PWD/target}/release/gcodec"
