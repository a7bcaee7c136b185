//! Names the target in the binary, and gives the bare-metal targets their memory layout.
use std::path::PathBuf;

fn main() {
    let target = std::env::var("TARGET").unwrap();
    println!("cargo:rustc-env=HIBI_TARGET={target}");
    let dir = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap());
    if target.starts_with("thumb") {
        // cortex-m-rt's link.x includes memory.x from the search path.
        println!("cargo:rustc-link-search={}", dir.display());
        println!("cargo:rustc-link-arg=-Tlink.x");
        println!("cargo:rerun-if-changed=memory.x");
    } else if target.starts_with("riscv32") {
        println!("cargo:rustc-link-arg=-T{}", dir.join("riscv32-virt.ld").display());
        println!("cargo:rerun-if-changed=riscv32-virt.ld");
    }
    println!("cargo:rerun-if-changed=build.rs");
}
