//! The checked-in header `include/hibi.h` is exactly what the pinned cbindgen generates
//! from `ffi/`. Set `HIBI_BLESS=1` to rewrite it after changing the C API.

use std::path::Path;

#[test]
fn header_is_fresh() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let ffi = root.join("ffi");
    let config = cbindgen::Config::from_file(ffi.join("cbindgen.toml")).expect("ffi/cbindgen.toml");
    let mut generated = Vec::new();
    cbindgen::Builder::new()
        .with_config(config)
        .with_src(ffi.join("src/lib.rs"))
        .with_src(root.join("core/src/mud/trace.rs"))
        .with_src(root.join("core/src/mud/network.rs"))
        .with_src(root.join("core/src/glass/output.rs"))
        .with_src(root.join("core/src/glass/fragments.rs"))
        .generate()
        .expect("cbindgen parses ffi/src")
        .write(&mut generated);
    let generated = String::from_utf8(generated).expect("the header is UTF-8");
    let path = root.join("include/hibi.h");
    if std::env::var_os("HIBI_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("write include/hibi.h");
        return;
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    if checked_in != generated {
        panic!(
            "include/hibi.h is stale; regenerate with `HIBI_BLESS=1 cargo test --test header`.\n{}",
            hibi_tests::line_diff(&checked_in, &generated)
        );
    }
}
