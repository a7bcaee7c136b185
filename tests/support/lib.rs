//! Helpers shared by the cross-crate tests in `tests/`.

use std::path::{Path, PathBuf};

/// A readable difference between two texts: every differing line, numbered, as
/// `-expected` / `+actual`, with a count of the lines that differ.
pub fn line_diff(expected: &str, actual: &str) -> String {
    let (old, new): (Vec<&str>, Vec<&str>) = (expected.lines().collect(), actual.lines().collect());
    let mut out = String::new();
    let mut differing = 0;
    for i in 0..old.len().max(new.len()) {
        let (a, b) = (old.get(i), new.get(i));
        if a != b {
            differing += 1;
            if differing <= 40 {
                if let Some(a) = a {
                    out += &format!("{:>5} -{a}\n", i + 1);
                }
                if let Some(b) = b {
                    out += &format!("{:>5} +{b}\n", i + 1);
                }
            }
        }
    }
    format!("{differing} line(s) differ (- checked in, + generated):\n{out}")
}

/// Compiler flags that build a C or C++ program under AddressSanitizer (with LeakSanitizer)
/// and UndefinedBehaviorSanitizer; any report ends the run with a failing status.
pub const SANITIZE_FLAGS: &[&str] =
    &["-fsanitize=address,undefined", "-fno-sanitize-recover=all", "-fno-omit-frame-pointer"];

/// The environment a sanitized program runs with: a refused allocation is a null pointer
/// (hibi reports `HIBI_ERROR_OUT_OF_MEMORY`), as from the C library, not an abort.
pub const ASAN_OPTIONS: (&str, &str) = ("ASAN_OPTIONS", "allocator_may_return_null=1");

/// Valgrind's command line: quiet (it prints only what it finds), and any error or leak a
/// failing exit status. (Still-reachable blocks are not errors: the panic hook hibi installs
/// once stays.)
pub const VALGRIND: &[&str] = &["valgrind", "-q", "--error-exitcode=1", "--leak-check=full"];

/// The workspace root.
pub fn workspace_root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The directory cargo builds this profile into (`target/debug` or `target/release`), found
/// from the running test binary (`target/<profile>/deps/<test>`).
pub fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    exe.parent().and_then(Path::parent).expect("target/<profile>/deps").to_path_buf()
}

/// FNV-1a, 64-bit: the hash of golden snapshots (one definition, in the scenes crate).
pub use hibi_scenes::fnv1a64;

/// Runs `call` on four threads at once and returns what each gave (for the read-only calls
/// that may share one object).
pub fn on_four_threads<T: Send>(call: impl Fn() -> T + Sync) -> Vec<T> {
    std::thread::scope(|s| {
        let threads: Vec<_> = (0..4).map(|_| s.spawn(&call)).collect();
        threads.into_iter().map(|t| t.join().expect("no panic")).collect()
    })
}
