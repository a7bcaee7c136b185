//! Names the target in the binary, and gives the bare-metal targets their memory layout.
use std::path::PathBuf;

fn main() {
    let target = std::env::var("TARGET").unwrap();
    println!("cargo:rustc-env=HIBI_TARGET={target}");
    let dir = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap());
    // The 64 KiB part (lm3s6965evb) runs only the 64 KiB scenes.
    println!("cargo::rustc-check-cfg=cfg(hibi_small)");
    if target.starts_with("thumb") {
        // cortex-m-rt's link.x includes memory.x (from the linker's working directory, this
        // one, or the search path): the part's layout, copied to OUT_DIR under that name (so
        // no memory.x may lie here).
        let (layout, small) =
            if target.starts_with("thumbv7m-") { ("lm3s6965.x", true) } else { ("mps2-an386.x", false) };
        let out = PathBuf::from(std::env::var("OUT_DIR").unwrap());
        std::fs::copy(dir.join(layout), out.join("memory.x")).unwrap();
        println!("cargo:rustc-link-search={}", out.display());
        println!("cargo:rustc-link-arg=-Tlink.x");
        println!("cargo:rerun-if-changed={layout}");
        if small {
            println!("cargo:rustc-cfg=hibi_small");
        }
    } else if target.starts_with("riscv32") {
        println!("cargo:rustc-link-arg=-T{}", dir.join("riscv32-virt.ld").display());
        println!("cargo:rerun-if-changed=riscv32-virt.ld");
    }
    println!("cargo:rerun-if-changed=build.rs");
}
