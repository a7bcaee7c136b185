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

/// Runs `command`, failing the test with its output unless it succeeds.
pub fn run(command: &mut std::process::Command) -> std::process::Output {
    let output = command.output().unwrap_or_else(|e| panic!("run {command:?}: {e}"));
    assert!(
        output.status.success(),
        "{command:?} failed ({}):\n{}\n{}",
        output.status,
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

/// What `command` prints, failing the test unless it succeeds.
pub fn stdout(command: &mut std::process::Command) -> String {
    String::from_utf8(run(command).stdout).expect("UTF-8 output")
}

/// The workspace root.
pub fn workspace_root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The machine's load average over the last minute, from Linux's `/proc/loadavg` (None where
/// there is none): the benches note it beside the ratios they write.
pub fn load_average() -> Option<f64> {
    std::fs::read_to_string("/proc/loadavg").ok()?.split_whitespace().next()?.parse().ok()
}

/// Writes `tables`, what one run of `command` measured, to `docs/src/generated/<file>`, the
/// part of the performance page that run makes, under a line naming the command and the load
/// average when the run started and ended (`load`); prints the path. Under Valgrind (which
/// preloads its `vgpreload` library into the program) the times are Valgrind's: the tables are
/// printed and the file is left as it is.
pub fn write_bench_tables(file: &str, command: &str, load: [Option<f64>; 2], tables: &str) {
    let load = match load {
        [Some(start), Some(end)] => format!("; load average {start:.1} as it started, {end:.1} as it ended"),
        _ => String::new(),
    };
    let text = format!(
        "<!-- Written by `{command}`; do not edit. -->\n\nOne run of `{command}` ({}, {}, {} logical CPUs{load}):\n\n{tables}",
        std::env::consts::ARCH,
        std::env::consts::OS,
        std::thread::available_parallelism().map_or(1, usize::from),
    );
    let path = format!("docs/src/generated/{file}");
    print!("\n{tables}");
    if std::env::var("LD_PRELOAD").is_ok_and(|preload| preload.contains("vgpreload")) {
        println!("\nunder Valgrind: {path} left as it is");
        return;
    }
    std::fs::write(workspace_root().join(&path), text).unwrap_or_else(|e| panic!("write {path}: {e}"));
    println!(
        "
wrote {path}"
    );
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

/// A command for an external tool the tests need (a compiler, `cmake`, `valgrind`, ...). When
/// the tool is not installed the test fails at once, naming it and the Debian package that
/// provides it (`./test` installs them), instead of failing to spawn deep inside the test.
pub fn tool(program: impl AsRef<std::ffi::OsStr>) -> std::process::Command {
    let program = program.as_ref();
    let found = if Path::new(program).components().count() > 1 {
        Path::new(program).is_file()
    } else {
        std::env::var_os("PATH")
            .map(|path| std::env::split_paths(&path).any(|dir| dir.join(program).is_file()))
            .unwrap_or(false)
    };
    if !found {
        let name = program.to_string_lossy();
        let package = match name.rsplit('/').next().unwrap_or(&name) {
            "cc" | "gcc" => "gcc",
            "c++" | "g++" => "g++",
            "clang" | "clang++" => "clang",
            "nm" | "readelf" | "ld" | "objcopy" | "ar" => "binutils",
            other => other,
        };
        panic!("`{name}` is not installed: install the Debian package `{package}` (`./test` installs what is missing)");
    }
    std::process::Command::new(program)
}

/// The native libraries a Rust static library needs on Linux
/// (`rustc --print native-static-libs`).
pub const NATIVE_STATIC_LIBS: &[&str] = &["-lgcc_s", "-lutil", "-lrt", "-lpthread", "-lm", "-ldl", "-lc"];

/// Builds libhibi.a and libhibi.so in this test's profile, once, in a target directory of its
/// own (so it never waits on the lock of the build that runs the tests).
pub fn c_library_dir() -> &'static Path {
    static DIR: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let target = workspace_root().join("target/c-link");
        let mut cargo = std::process::Command::new(env!("CARGO"));
        cargo.args(["build", "-p", "hibi-ffi", "--target-dir"]).arg(&target);
        let profile = if cfg!(debug_assertions) { "debug" } else { "release" };
        if profile == "release" {
            cargo.arg("--release");
        }
        let status = cargo.current_dir(workspace_root()).status().expect("run cargo");
        assert!(status.success(), "cargo build -p hibi-ffi failed");
        let dir = target.join(profile);
        // The shared library's SONAME is libhibi.so.MAJOR (ffi/build.rs): programs linked to
        // it look for that name, which the install step (ffi/install) lays out as a symlink.
        let soname = dir.join(concat!("libhibi.so.", env!("CARGO_PKG_VERSION_MAJOR")));
        match std::os::unix::fs::symlink("libhibi.so", &soname) {
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
            made => made.expect("symlink libhibi.so.MAJOR"),
        }
        dir
    })
}

/// The `hibi` tool in this test's profile, built once in a target directory of its own: the
/// directory it is in.
pub fn cli_dir() -> &'static Path {
    static DIR: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let target = workspace_root().join("target/docs-cli");
        let mut cargo = std::process::Command::new(env!("CARGO"));
        cargo.args(["build", "-p", "hibi-cli", "--target-dir"]).arg(&target);
        if !cfg!(debug_assertions) {
            cargo.arg("--release");
        }
        let status = cargo.current_dir(workspace_root()).status().expect("run cargo");
        assert!(status.success(), "cargo build -p hibi-cli failed");
        target.join(if cfg!(debug_assertions) { "debug" } else { "release" })
    })
}

/// The Rust blocks of the README and the guide, run as doctests (`tests/docs.rs` checks that
/// every page with a Rust block is here).
#[cfg(doctest)]
mod guide {
    #[doc = include_str!("../../README.md")]
    struct Readme;
    #[doc = include_str!("../../docs/src/getting-started.md")]
    struct GettingStarted;
    #[doc = include_str!("../../docs/src/rust.md")]
    struct RustApi;
}

/// Runs test `test` of the running test binary again, alone (an ignored one too), under
/// Callgrind with collection only inside the function `toggle` (a `no_mangle` function the
/// test calls), with `env` set so that the re-run knows which case to do. Returns what the re-run printed and the
/// instructions counted; fails when the re-run fails or Callgrind counted nothing.
pub fn callgrind_this_test(test: &str, toggle: &str, env: (&str, &str)) -> (String, u64) {
    let (stdout, text, case) = callgrind_rerun(test, toggle, env);
    let instructions = text
        .lines()
        .find_map(|l| l.strip_prefix("summary: ").or_else(|| l.strip_prefix("totals: ")))
        .and_then(|s| s.trim().parse().ok())
        .unwrap_or_else(|| panic!("{case}: no instruction count in Callgrind's output"));
    (stdout, instructions)
}

/// [`callgrind_this_test`] with collection inside every function whose name matches `toggle`
/// (Callgrind's wildcards: `hibi_test_phase_*`), and the instructions counted in each of them,
/// what it calls included, by name (functions that were never called are absent). Several
/// patterns are separated by `|`; each toggles collection on entry and exit, so a pattern of
/// functions called inside the counted ones (`hibi_bench_*|__mem*`) leaves them out.
pub fn callgrind_this_test_by_function(
    test: &str,
    toggle: &str,
    env: (&str, &str),
) -> (String, std::collections::BTreeMap<String, u64>) {
    let (stdout, text, _) = callgrind_rerun(test, toggle, env);
    (stdout, inclusive_costs(&text))
}

/// [`callgrind_this_test_by_function`] for a program without libtest's harness (a bench):
/// runs the running executable again with `args` under Callgrind.
pub fn callgrind_this_program_by_function(
    args: &[&str],
    toggle: &str,
    env: (&str, &str),
) -> (String, std::collections::BTreeMap<String, u64>) {
    let (stdout, text, _) = callgrind_run(args, toggle, env);
    (stdout, inclusive_costs(&text))
}

/// Runs `test` again under Callgrind (see [`callgrind_this_test`]); returns what it printed,
/// Callgrind's output (names written out, not compressed) and the case's name for messages.
fn callgrind_rerun(test: &str, toggle: &str, env: (&str, &str)) -> (String, String, String) {
    callgrind_run(&[test, "--exact", "--include-ignored", "--nocapture", "--test-threads=1"], toggle, env)
}

/// Runs the running executable again with `args` under Callgrind (see [`callgrind_rerun`]).
fn callgrind_run(args: &[&str], toggle: &str, env: (&str, &str)) -> (String, String, String) {
    let test = args.first().copied().unwrap_or("run");
    let exe = std::env::current_exe().expect("the test binary");
    let out = exe.with_file_name(format!("{test}_{}.callgrind", env.1));
    let _ = std::fs::remove_file(&out);
    let run = tool("valgrind")
        .args(["-q", "--tool=callgrind", "--collect-atstart=no", "--compress-strings=no"])
        .args(toggle.split('|').map(|t| format!("--toggle-collect={t}")))
        .arg(format!("--callgrind-out-file={}", out.display()))
        .arg(&exe)
        .args(args)
        .env(env.0, env.1)
        .output()
        .expect("run valgrind");
    let stdout = String::from_utf8_lossy(&run.stdout).into_owned();
    let case = format!("{test} with {}={}", env.0, env.1);
    assert!(run.status.success(), "{case}: {}\n{stdout}\n{}", run.status, String::from_utf8_lossy(&run.stderr));
    let text = std::fs::read_to_string(&out).expect("Callgrind's output");
    (stdout, text, case)
}

/// The instructions counted in each function of a Callgrind output with one event (Ir), what
/// it calls included: the cost lines of its `fn=` blocks, its own lines and those that follow
/// a `calls=` line (the called function's cost, inclusive).
fn inclusive_costs(text: &str) -> std::collections::BTreeMap<String, u64> {
    let mut costs = std::collections::BTreeMap::new();
    let mut current: Option<String> = None;
    for line in text.lines() {
        if let Some(name) = line.strip_prefix("fn=") {
            current = Some(name.to_owned());
        } else if line.starts_with(|c: char| c.is_ascii_digit() || matches!(c, '+' | '-' | '*'))
            && let Some(name) = &current
        {
            let cost: u64 = line.split_whitespace().nth(1).and_then(|c| c.parse().ok()).unwrap_or(0);
            *costs.entry(name.clone()).or_insert(0) += cost;
        }
    }
    costs
}

/// Owned buffers for every layer a render can write, of `pixels` pixels, and the scratch of a
/// `width × height` tile: what a test hands a render to draw everything a model has at once.
#[derive(Clone, Debug, PartialEq)]
pub struct EveryLayer {
    pub mask: Vec<u8>,
    pub height: Vec<f32>,
    pub height16: Vec<u16>,
    pub normal: Vec<[f32; 3]>,
    pub normal_rgb8: Vec<[u8; 3]>,
    pub time: Vec<f32>,
    pub cell: Vec<u32>,
    pub preview: Vec<[u8; 4]>,
    pub scratch: Vec<u32>,
}

impl EveryLayer {
    /// Buffers for a `width × height` tile, filled with a pattern no render writes whole.
    pub fn new(width: u32, height: u32) -> EveryLayer {
        let pixels = width as usize * height as usize;
        EveryLayer {
            mask: vec![7; pixels],
            height: vec![-7.0; pixels],
            height16: vec![7; pixels],
            normal: vec![[-7.0; 3]; pixels],
            normal_rgb8: vec![[7; 3]; pixels],
            time: vec![-7.0; pixels],
            cell: vec![7; pixels],
            preview: vec![[7; 4]; pixels],
            scratch: vec![0; hibi_core::raster::scratch_len(width, height).expect("a small tile")],
        }
    }

    /// The core's layers over these buffers: every one but `time` (`crack`: false, for skin) or
    /// `cell` (`crack`: true, for mud and glass).
    pub fn layers(&mut self, crack: bool) -> hibi_core::raster::Layers<'_> {
        hibi_core::raster::Layers {
            mask: Some(&mut self.mask),
            height: Some(&mut self.height),
            height16: Some(&mut self.height16),
            normal: Some(&mut self.normal),
            normal_rgb8: Some(&mut self.normal_rgb8),
            time: crack.then_some(&mut self.time[..]),
            cell: (!crack).then_some(&mut self.cell[..]),
            preview: Some(&mut self.preview),
            scratch: Some(&mut self.scratch),
        }
    }

    /// The layers' pixels `(x, y)` of a `width`-wide tile, as one comparable record (floats as
    /// bits, so that NaN and infinity compare exactly); the scratch is left out.
    pub fn pixel(&self, width: u32, x: u32, y: u32) -> [u32; 10] {
        let i = (y * width + x) as usize;
        let n = self.normal[i];
        let c = self.normal_rgb8[i];
        let p = self.preview[i];
        [
            u32::from(self.mask[i]),
            self.height[i].to_bits(),
            u32::from(self.height16[i]),
            n[0].to_bits(),
            n[1].to_bits(),
            n[2].to_bits(),
            u32::from_le_bytes([c[0], c[1], c[2], 0]),
            self.time[i].to_bits(),
            self.cell[i],
            u32::from_le_bytes(p),
        ]
    }
}

/// What tests/consumer/main.cpp prints, built against any form of the library (installed,
/// a CMake subproject, the release archive).
pub fn consumer_cpp_output() -> String {
    let version = env!("CARGO_PKG_VERSION");
    format!(
        "hibi_version() {version}, macros {version}, equal: yes\nmud: cracks\nglass: fragments\n\
         skin: 1 cells, 4096 heights\nunknown preset: status 1093\n"
    )
}

/// What tests/consumer/main.c prints: the versions, hibi's first draw for seed 42 and
/// stream 7, and the status of a call on a null object.
pub fn consumer_c_output() -> String {
    let version = env!("CARGO_PKG_VERSION");
    let draw = hibi_core::Rng::from_key(42, 7).next_u32();
    let null = hibi::HIBI_ERROR_NULL_POINTER;
    format!("hibi_version() {version}, macros {version}, equal: yes\ndraw: {draw}\nNULL rng: status {null}\n")
}
