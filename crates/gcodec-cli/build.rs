//! Links the `gcodec` executable at a fixed address on GNU/Linux (not as a
//! position-independent executable).
//!
//! A PIE is relocated by the dynamic loader at every start: about 12,000
//! relative relocations, and every page of `.data.rel.ro` they touch is
//! copied on write. That was a fifth of the instructions and a fifth of
//! the page faults of a short program's run (issue 20,
//! docs/performance.md, "Issue 20: the third measurement"). The code is
//! still compiled position-independent; the linker resolves those
//! addresses once. The trade-off: the executable's own address is not
//! randomised (its libraries, stack and heap still are), which matters
//! little for a compiler reading local files. `GCODEC_PIE=1` at build time
//! keeps the default.

fn main() {
    println!("cargo::rerun-if-env-changed=GCODEC_PIE");
    let linux = std::env::var("CARGO_CFG_TARGET_OS").is_ok_and(|os| os == "linux")
        && std::env::var("CARGO_CFG_TARGET_ENV").is_ok_and(|env| env == "gnu");
    let pie = std::env::var("GCODEC_PIE").is_ok_and(|v| v == "1");
    if linux && !pie {
        println!("cargo::rustc-link-arg-bins=-no-pie");
    }
}
