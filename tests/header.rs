//! The checked-in header `include/hibi.h` is exactly what the pinned cbindgen generates
//! from `ffi/`. Set `HIBI_BLESS=1` to rewrite it after changing the C API.

use std::path::Path;

#[test]
fn header_is_fresh() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let ffi = root.join("ffi");
    let config = cbindgen::Config::from_file(ffi.join("cbindgen.toml")).expect("ffi/cbindgen.toml");
    // The C layer's per-model functions come from one macro (`ffi/src/object.rs`), so cbindgen
    // reads the crate with its macros expanded: `cargo rustc -- -Zunpretty=expanded`, which a
    // stable toolchain runs with RUSTC_BOOTSTRAP=1, in a target directory of its own.
    // SAFETY: set before any thread of this test process starts a child.
    unsafe {
        std::env::set_var("RUSTC_BOOTSTRAP", "1");
        std::env::set_var("CARGO_EXPAND_TARGET_DIR", Path::new(env!("CARGO_TARGET_TMPDIR")).join("expand"));
    }
    let mut generated = Vec::new();
    cbindgen::Builder::new()
        .with_config(config)
        .with_crate(&ffi)
        .with_parse_expand(&["hibi-ffi"])
        .with_src(root.join("core/src/mud/trace.rs"))
        .with_src(root.join("core/src/mud/network.rs"))
        .with_src(root.join("core/src/glass/output.rs"))
        .with_src(root.join("core/src/polygon/ring.rs"))
        .with_src(root.join("core/src/polygon/pieces.rs"))
        .with_src(root.join("core/src/raster/tile.rs"))
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

/// The header compiles without a warning in C99, C11 and C++17 under gcc and clang at
/// `-Wall -Wextra -Wpedantic -Werror` (`.ci/run` installs clang).
#[test]
fn header_is_warning_free_in_c99_c11_and_cpp17_with_gcc_and_clang() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let c = dir.join("header_only.c");
    let cpp = dir.join("header_only.cpp");
    let unit = "#include \"hibi.h\"\nint main(void) { return hibi_version() == 0; }\n";
    std::fs::write(&c, unit).expect("write the C unit");
    std::fs::write(&cpp, unit.replace("(void)", "()")).expect("write the C++ unit");
    for (compiler, standard, source) in [
        ("gcc", "c99", &c),
        ("gcc", "c11", &c),
        ("g++", "c++17", &cpp),
        ("clang", "c99", &c),
        ("clang", "c11", &c),
        ("clang++", "c++17", &cpp),
    ] {
        let output = hibi_tests::tool(compiler)
            .arg(format!("-std={standard}"))
            .args(["-Wall", "-Wextra", "-Wpedantic", "-Werror", "-fsyntax-only", "-I"])
            .arg(root.join("include"))
            .arg(source)
            .output()
            .unwrap_or_else(|e| panic!("run {compiler} (install it: .ci/run does): {e}"));
        assert!(
            output.status.success(),
            "{compiler} -std={standard}: the header warns:\n{}",
            String::from_utf8_lossy(&output.stderr)
        );
    }
}

/// Every `HIBI_*` constant the header, the C++ wrapper, the examples and the docs cite is one
/// `include/hibi.h` defines (a name cited but not defined, such as a `HIBI_GLASS_LARGE` in the
/// header, fails here). A name followed by `*` is a family (`HIBI_MUD_LAYER_*`), not a constant.
#[test]
fn every_cited_constant_is_defined() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let read = |path: &Path| std::fs::read_to_string(path).unwrap_or_else(|e| panic!("read {}: {e}", path.display()));
    let header = read(&root.join("include/hibi.h"));
    let defined: std::collections::BTreeSet<&str> =
        header.lines().filter_map(|l| l.strip_prefix("#define ")?.split_whitespace().next()).collect();
    // Not constants: the wrapper's include guard, the environment variable that rewrites the
    // header (`header_is_fresh`), the CMake variable that picks the static library, and the
    // wrapper's mode macros (`HIBI_NO_EXCEPTIONS`, which a user defines, and `HIBI_EXCEPTIONS`,
    // which the wrapper defines).
    let not_constants = ["HIBI_HPP", "HIBI_BLESS", "HIBI_STATIC", "HIBI_NO_EXCEPTIONS", "HIBI_EXCEPTIONS"];
    let mut sources = vec![root.join("include/hibi.h"), root.join("include/hibi.hpp"), root.join("README.md")];
    for dir in ["docs", "c_examples"] {
        let mut entries: Vec<_> = std::fs::read_dir(root.join(dir)).expect(dir).map(|e| e.expect(dir).path()).collect();
        entries.sort();
        sources.extend(entries.into_iter().filter(|p| {
            p.extension().is_some_and(|e| ["md", "c", "cpp", "h", "hpp"].contains(&e.to_str().unwrap_or("")))
        }));
    }
    let mut undefined = Vec::new();
    for path in &sources {
        let text = read(path);
        let bytes = text.as_bytes();
        let mut at = 0;
        while let Some(found) = text[at..].find("HIBI_") {
            let start = at + found;
            let mut end = start + 5;
            while end < bytes.len()
                && (bytes[end].is_ascii_uppercase() || bytes[end].is_ascii_digit() || bytes[end] == b'_')
            {
                end += 1;
            }
            at = end;
            let name = &text[start..end];
            let word_start = start == 0 || !(bytes[start - 1].is_ascii_alphanumeric() || bytes[start - 1] == b'_');
            let family = name.ends_with('_') && bytes.get(end) == Some(&b'*');
            if word_start && !family && !defined.contains(name) && !not_constants.contains(&name) {
                undefined.push(format!("{}: {name}", path.strip_prefix(root).unwrap_or(path).display()));
            }
        }
    }
    assert!(undefined.is_empty(), "cited but not defined in include/hibi.h:\n{}", undefined.join("\n"));
}
