//! hibi-core builds into a `#![no_std]` static library that has no global allocator: the
//! proof that the core uses neither std nor alloc (`tests/no_std_check`).

use std::process::Command;

use hibi_tests::workspace_root;

#[test]
fn core_builds_without_std_or_alloc() {
    let root = workspace_root();
    let output = Command::new(env!("CARGO"))
        .args(["build", "--manifest-path"])
        .arg(root.join("tests/no_std_check/Cargo.toml"))
        .arg("--target-dir")
        .arg(root.join("target/no-std-check"))
        .output()
        .expect("run cargo");
    assert!(
        output.status.success(),
        "hibi-core does not build without std and alloc:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let lib = root.join("target/no-std-check/debug/libhibi_no_std_check.a");
    let symbols = hibi_tests::tool("nm").arg("-C").arg(&lib).output().expect("run nm");
    let symbols = String::from_utf8_lossy(&symbols.stdout);
    assert!(symbols.contains("T hibi_no_std_probe"), "the probe is not in {}", lib.display());
    for forbidden in ["__rust_alloc", "__rdl_alloc", "std::"] {
        assert!(!symbols.contains(forbidden), "{forbidden} is linked into the no_std library");
    }
}
