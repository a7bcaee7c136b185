//! Every shell script in the repository parses: `bash -n` (or `sh -n` for a POSIX `sh`
//! script) on each tracked file that starts with a shell's `#!` line. A quoting slip in a
//! set-up script otherwise shows only when CI runs it on a fresh machine.

use std::process::Command;

/// The tracked files whose first line runs a shell, with that shell.
fn scripts() -> Vec<(String, &'static str)> {
    let root = hibi_tests::workspace_root();
    let listed = Command::new("git").args(["ls-files", "-z"]).current_dir(root).output().expect("run git ls-files");
    assert!(listed.status.success(), "git ls-files failed");
    String::from_utf8_lossy(&listed.stdout)
        .split('\0')
        .filter(|f| !f.is_empty())
        .filter_map(|f| {
            let text = std::fs::read(root.join(f)).ok()?;
            let first = text.split(|&b| b == b'\n').next()?;
            let first = String::from_utf8_lossy(first);
            let shell = if !first.starts_with("#!") {
                return None;
            } else if first.contains("bash") {
                "bash"
            } else if first.ends_with("/sh") || first.ends_with(" sh") {
                "sh"
            } else {
                return None;
            };
            Some((f.to_owned(), shell))
        })
        .collect()
}

#[test]
fn every_shell_script_parses() {
    let scripts = scripts();
    for name in ["test", ".ci/run", "targets/run"] {
        assert!(scripts.iter().any(|(f, _)| f == name), "{name} is found as a script: {scripts:?}");
    }
    let root = hibi_tests::workspace_root();
    let broken: Vec<String> = scripts
        .iter()
        .filter_map(|(file, shell)| {
            let out = Command::new(shell).arg("-n").arg(file).current_dir(root).output().expect("run the shell");
            (!out.status.success()).then(|| format!("{file}: {}", String::from_utf8_lossy(&out.stderr).trim()))
        })
        .collect();
    assert!(broken.is_empty(), "scripts that do not parse:\n{}", broken.join("\n"));
}
