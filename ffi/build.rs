//! Gives the shared library an ELF SONAME, `libhibi.so.MAJOR`, so that programs linked to it
//! load any later library of the same major version (`ffi/install` lays out the file and its
//! symlinks). Other targets are left as cargo builds them.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    if ["linux", "android", "freebsd", "netbsd", "openbsd", "dragonfly"].contains(&os.as_str()) {
        let major = std::env::var("CARGO_PKG_VERSION_MAJOR").expect("cargo sets CARGO_PKG_VERSION_MAJOR");
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libhibi.so.{major}");
    }
}
