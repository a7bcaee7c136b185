//! The C library's ABI: `abi/check` compares `libhibi.so` (dev profile, full DWARF) with its
//! committed description, `abi/libhibi.so.MAJOR.abi` (libabigail's abidw XML) and
//! `abi/libhibi.so.MAJOR.constants`. The library must match it or only add to it.
//!
//! The other tests prove the check can fail: each gives it a description changed the way an
//! incompatible library would differ (a struct one field longer, a function more, a constant
//! of another value) and expects the verdict "incompatible", with abidiff's report naming the
//! change; an addition passes and is reported; a library without debug info, or without the
//! members of a struct the header defines, stops the check instead of passing it on symbol
//! names alone.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use hibi_tests::workspace_root;

const MAJOR: &str = env!("CARGO_PKG_VERSION_MAJOR");

/// `libhibi.so` of the dev profile (full DWARF, unlike the release profile's line tables),
/// built once in the C link tests' target directory.
fn library() -> &'static Path {
    static LIBRARY: OnceLock<PathBuf> = OnceLock::new();
    LIBRARY.get_or_init(|| {
        let root = workspace_root();
        let target = root.join("target/c-link");
        let status = Command::new(env!("CARGO"))
            .args(["build", "--quiet", "-p", "hibi-ffi", "--target-dir"])
            .arg(&target)
            .arg("--manifest-path")
            .arg(root.join("Cargo.toml"))
            .status()
            .expect("run cargo build");
        assert!(status.success(), "cargo build -p hibi-ffi failed");
        target.join("debug/libhibi.so")
    })
}

fn committed(ext: &str) -> PathBuf {
    workspace_root().join(format!("abi/libhibi.so.{MAJOR}.{ext}"))
}

/// Runs `abi/check` on the library with extra arguments: its exit code and its output.
fn check(args: &[&std::ffi::OsStr]) -> (i32, String) {
    let output = Command::new(workspace_root().join("abi/check"))
        .arg("--library")
        .arg(library())
        .args(args)
        .output()
        .expect("run abi/check");
    let text = format!("{}{}", String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    (output.status.code().expect("abi/check exited"), text)
}

/// A fresh scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("abi-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create a scratch directory");
    dir
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("read {}: {e}", path.display()))
}

/// Writes `text` as `name` in `dir` and returns its path.
fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write a scratch file");
    path
}

/// The element `<tag name='NAME' …>…</tag>` of the description, from its opening to its end.
fn element<'a>(xml: &'a str, tag: &str, name: &str) -> &'a str {
    let open = format!("<{tag} name='{name}' ");
    let start = xml.find(&open).unwrap_or_else(|| panic!("no {open} in the description"));
    let close = format!("</{tag}>");
    let end = start + xml[start..].find(&close).expect("the element's end") + close.len();
    &xml[start..end]
}

#[test]
fn the_library_has_the_committed_abi_or_adds_to_it() {
    let (code, output) = check(&[]);
    println!("{output}");
    assert_eq!(code, 0, "abi/check:\n{output}");
    assert!(output.contains(&format!("libhibi.so.{MAJOR}")), "{output}");
}

#[test]
fn the_committed_description_is_of_the_current_soname() {
    let xml = read(&committed("abi"));
    assert!(
        xml.lines().next().is_some_and(|l| l.contains(&format!("soname='libhibi.so.{MAJOR}'"))),
        "abi/libhibi.so.{MAJOR}.abi describes another SONAME"
    );
    // One description: that of the SONAME the library has now.
    let descriptions: Vec<_> = std::fs::read_dir(workspace_root().join("abi"))
        .expect("abi/")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("libhibi.so."))
        .collect();
    let mut expected = vec![format!("libhibi.so.{MAJOR}.abi"), format!("libhibi.so.{MAJOR}.constants")];
    let mut found = descriptions.clone();
    found.sort();
    expected.sort();
    assert_eq!(found, expected);
}

#[test]
fn a_struct_one_field_shorter_is_incompatible() {
    // The description's hibi_mud_params has one more field (a u64, as its seed) at its end:
    // the library dropped a field (and shrank the struct), as a careless edit would.
    let xml = read(&committed("abi"));
    let params = element(&xml, "class-decl", "hibi_mud_params");
    let bits: u32 = params
        .split("size-in-bits='")
        .nth(1)
        .and_then(|s| s.split('\'').next())
        .and_then(|s| s.parse().ok())
        .expect("the struct's size");
    let u64_type = params
        .split("<var-decl name='seed' type-id='")
        .nth(1)
        .and_then(|s| s.split('\'').next())
        .expect("the seed field's type");
    let longer =
        params.replacen(&format!("size-in-bits='{bits}'"), &format!("size-in-bits='{}'", bits + 64), 1).replace(
            "</class-decl>",
            &format!(
                "  <data-member access='public' layout-offset-in-bits='{bits}'>\n            \
             <var-decl name='spare' type-id='{u64_type}' visibility='default'/>\n          \
             </data-member>\n        </class-decl>"
            ),
        );
    let dir = scratch("field");
    let baseline = write(&dir, "changed.abi", &xml.replacen(params, &longer, 1));
    let (code, output) = check(&["--baseline".as_ref(), baseline.as_os_str()]);
    assert_eq!(code, 1, "abi/check passed a struct that lost a field:\n{output}");
    assert!(output.contains("hibi_mud_params"), "{output}");
    assert!(output.contains(&format!("type size changed from {} to {bits}", bits + 64)), "{output}");
    assert!(output.contains("'u64 spare', at offset"), "{output}");
    assert!(output.contains("INCOMPATIBLE"), "{output}");
}

#[test]
fn reordered_fields_are_incompatible() {
    // The description has hibi_mud_params' first two fields the other way round.
    let xml = read(&committed("abi"));
    let params = element(&xml, "class-decl", "hibi_mud_params");
    let first = params.find("layout-offset-in-bits='0'").expect("a first field");
    let second = params.find("layout-offset-in-bits='32'").expect("a second field");
    let mut swapped = params.to_string();
    swapped.replace_range(second..second + "layout-offset-in-bits='32'".len(), "layout-offset-in-bits='0'");
    swapped.replace_range(first..first + "layout-offset-in-bits='0'".len(), "layout-offset-in-bits='32'");
    let dir = scratch("order");
    let baseline = write(&dir, "changed.abi", &xml.replacen(params, &swapped, 1));
    let (code, output) = check(&["--baseline".as_ref(), baseline.as_os_str()]);
    assert_eq!(code, 1, "abi/check passed reordered fields:\n{output}");
    assert!(output.contains("hibi_mud_params"), "{output}");
    assert!(output.contains("offset changed"), "{output}");
}

#[test]
fn a_removed_function_is_incompatible() {
    // The description has a function the library lacks: hibi_mud_destroy's twin.
    let xml = read(&committed("abi"));
    let symbol =
        xml.lines().find(|l| l.contains("<elf-symbol name='hibi_mud_destroy' ")).expect("hibi_mud_destroy's symbol");
    let decl = element(&xml, "function-decl", "hibi_mud_destroy");
    let changed = xml
        .replacen(symbol, &format!("{symbol}\n{}", symbol.replace("hibi_mud_destroy", "hibi_mud_discard")), 1)
        .replacen(decl, &format!("{decl}\n        {}", decl.replace("hibi_mud_destroy", "hibi_mud_discard")), 1);
    let dir = scratch("removed");
    let baseline = write(&dir, "changed.abi", &changed);
    let (code, output) = check(&["--baseline".as_ref(), baseline.as_os_str()]);
    assert_eq!(code, 1, "abi/check passed a removed function:\n{output}");
    assert!(output.contains("1 Removed function"), "{output}");
    assert!(output.contains("hibi_mud_discard"), "{output}");
}

#[test]
fn an_added_function_is_compatible_and_reported() {
    // The description lacks hibi_mud_destroy: the library adds it.
    let xml = read(&committed("abi"));
    let symbol =
        xml.lines().find(|l| l.contains("<elf-symbol name='hibi_mud_destroy' ")).expect("hibi_mud_destroy's symbol");
    let decl = element(&xml, "function-decl", "hibi_mud_destroy");
    let older = xml.replacen(&format!("{symbol}\n"), "", 1).replacen(decl, "", 1);
    let dir = scratch("added");
    let baseline = write(&dir, "older.abi", &older);
    let (code, output) = check(&["--baseline".as_ref(), baseline.as_os_str()]);
    assert_eq!(code, 0, "abi/check refused an addition:\n{output}");
    assert!(output.contains("1 Added function"), "{output}");
    assert!(output.contains("hibi_mud_destroy"), "{output}");
    assert!(output.contains("with additions"), "{output}");
}

#[test]
fn a_constant_of_another_value_is_incompatible_and_a_new_one_compatible() {
    let constants = read(&committed("constants"));
    let first = constants.lines().next().expect("a constant");
    let (name, value) = first.split_once(' ').expect("NAME VALUE");
    let dir = scratch("constants");

    let other: u64 = value.parse::<u64>().map(|v| v + 1).expect("a number");
    let changed = write(&dir, "changed", &constants.replacen(first, &format!("{name} {other}"), 1));
    let (code, output) = check(&["--constants".as_ref(), changed.as_os_str()]);
    assert_eq!(code, 1, "abi/check passed a changed constant:\n{output}");
    assert!(output.contains(&format!("constant {name} changed from {other} to {value}")), "{output}");

    let older = write(&dir, "older", &constants.replacen(&format!("{first}\n"), "", 1));
    let (code, output) = check(&["--constants".as_ref(), older.as_os_str()]);
    assert_eq!(code, 0, "abi/check refused a new constant:\n{output}");
    assert!(output.contains(&format!("1 added constants: {name}")), "{output}");
}

#[test]
fn a_library_without_debug_info_stops_the_check() {
    // Without DWARF abidiff would compare symbol names only and pass a changed struct.
    let dir = scratch("stripped");
    let stripped = dir.join("libhibi.so");
    let status =
        Command::new("objcopy").arg("--strip-debug").arg(library()).arg(&stripped).status().expect("run objcopy");
    assert!(status.success());
    let output = Command::new(workspace_root().join("abi/check"))
        .arg("--library")
        .arg(&stripped)
        .output()
        .expect("run abi/check");
    let text = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{text}");
    assert!(text.contains("has no DWARF"), "{text}");
}

#[test]
fn a_struct_missing_from_the_debug_info_stops_the_check() {
    // A header struct the DWARF does not describe (as with line tables only) stops the check.
    let header = read(&workspace_root().join("include/hibi.h"));
    let extra = "typedef struct hibi_mud_absent {\n  uint32_t value;\n} hibi_mud_absent;\n";
    let dir = scratch("absent");
    let path = write(&dir, "hibi.h", &format!("{header}\n{extra}"));
    let (code, output) = check(&["--header".as_ref(), path.as_os_str()]);
    assert_eq!(code, 2, "{output}");
    assert!(output.contains("lacks the members of struct hibi_mud_absent"), "{output}");
}

#[test]
fn update_refuses_an_incompatible_change_and_records_an_addition() {
    // abi/update writes the description it compares with: here a copy of the committed one.
    let xml = read(&committed("abi"));
    let constants = committed("constants");
    let dir = scratch("update");

    // One function more in the description: the library removed it, and the update refuses.
    let symbol =
        xml.lines().find(|l| l.contains("<elf-symbol name='hibi_mud_destroy' ")).expect("hibi_mud_destroy's symbol");
    let decl = element(&xml, "function-decl", "hibi_mud_destroy");
    let removed = xml
        .replacen(symbol, &format!("{symbol}\n{}", symbol.replace("hibi_mud_destroy", "hibi_mud_discard")), 1)
        .replacen(decl, &format!("{decl}\n        {}", decl.replace("hibi_mud_destroy", "hibi_mud_discard")), 1);
    let baseline = write(&dir, "removed.abi", &removed);
    let kept = write(&dir, "removed.constants", &read(&constants));
    let (code, output) = check(&[
        "--update".as_ref(),
        "--baseline".as_ref(),
        baseline.as_os_str(),
        "--constants".as_ref(),
        kept.as_os_str(),
    ]);
    assert_eq!(code, 1, "abi/update accepted a removed function:\n{output}");
    assert_eq!(read(&baseline), removed, "abi/update rewrote the description of an incompatible library");

    // One function fewer: an addition, recorded.
    let older = xml.replacen(&format!("{symbol}\n"), "", 1).replacen(decl, "", 1);
    let baseline = write(&dir, "older.abi", &older);
    let (code, output) = check(&[
        "--update".as_ref(),
        "--baseline".as_ref(),
        baseline.as_os_str(),
        "--constants".as_ref(),
        kept.as_os_str(),
    ]);
    assert_eq!(code, 0, "abi/update refused an addition:\n{output}");
    assert!(read(&baseline).contains("<function-decl name='hibi_mud_destroy' "), "abi/update did not record it");
    let (code, output) = check(&["--baseline".as_ref(), baseline.as_os_str()]);
    assert_eq!(code, 0, "{output}");
    assert!(!output.contains("Added function"), "the recorded description still lacks an addition:\n{output}");
}
