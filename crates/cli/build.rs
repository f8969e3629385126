//! Links the `swarf` binary as a position-dependent executable on x86-64 Linux.
//!
//! A position-independent one has some fifteen thousand addresses in its tables rewritten by
//! the dynamic loader at every start, which touches (and copies) every page they are on: about
//! a third of a millisecond, a few percent of a long program's run. Linked at a fixed address
//! they are written once, when it is linked. The libraries it loads still go where the system
//! puts them.

fn main() {
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let env = std::env::var("CARGO_CFG_TARGET_ENV").unwrap_or_default();
    let arch = std::env::var("CARGO_CFG_TARGET_ARCH").unwrap_or_default();
    if os == "linux" && env == "gnu" && arch == "x86_64" {
        println!("cargo:rustc-link-arg-bin=swarf=-no-pie");
    }
    println!("cargo:rerun-if-changed=build.rs");
}
