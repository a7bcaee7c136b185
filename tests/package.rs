//! Packaging: `ffi/install` lays out the C library, its headers, a pkg-config file and a CMake
//! package under a prefix; an out-of-tree C++ program (`tests/consumer/`) builds against the
//! install through pkg-config and through CMake, shared and static, and runs. The shared
//! library's SONAME, the header's version macros, the symbols the libraries export, and a
//! program linking libhibi.a next to a second Rust static library (`tests/second_rust_lib/`)
//! are checked here too. Both programs also run clean under AddressSanitizer +
//! UndefinedBehaviorSanitizer and under Valgrind, and a fully static (`-static`) consumer
//! links without a warning from glibc and runs.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use hibi_core::Rng;
use hibi_tests::{ASAN_OPTIONS, SANITIZE_FLAGS, VALGRIND, run, stdout, workspace_root};

const MAJOR: &str = env!("CARGO_PKG_VERSION_MAJOR");
const VERSION: &str = env!("CARGO_PKG_VERSION");

fn profile() -> &'static str {
    if cfg!(debug_assertions) { "debug" } else { "release" }
}

/// Installs into a prefix of this profile's own under CARGO_TARGET_TMPDIR, once, building in
/// the C link tests' target directory (`target/c-link`, shared with tests/c_examples.rs).
fn prefix() -> &'static Path {
    static PREFIX: OnceLock<PathBuf> = OnceLock::new();
    PREFIX.get_or_init(|| {
        let prefix = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("prefix-{}", profile()));
        let _ = std::fs::remove_dir_all(&prefix);
        let root = workspace_root();
        run(Command::new(root.join("ffi/install"))
            .arg("--prefix")
            .arg(&prefix)
            .args(["--profile", if profile() == "debug" { "dev" } else { "release" }])
            .arg("--target-dir")
            .arg(root.join("target/c-link"))
            .env("CARGO", env!("CARGO")));
        prefix
    })
}

/// The directory cargo built the libraries in (before the install step).
fn built_dir() -> PathBuf {
    prefix();
    workspace_root().join("target/c-link").join(profile())
}

/// A fresh directory for one test's build products.
fn scratch_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("package-{}-{name}", profile()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create a build directory");
    dir
}

#[test]
fn install_lays_out_libraries_headers_and_package_files() {
    let prefix = prefix();
    for file in [
        "lib/libhibi.a",
        "include/hibi.h",
        "include/hibi.hpp",
        "lib/pkgconfig/hibi.pc",
        "lib/cmake/hibi/hibiConfig.cmake",
        "lib/cmake/hibi/hibiConfigVersion.cmake",
    ] {
        assert!(prefix.join(file).is_file(), "no {file} under {}", prefix.display());
    }
    let lib = prefix.join("lib");
    assert!(lib.join(format!("libhibi.so.{VERSION}")).is_file());
    let link = |name: &str| std::fs::read_link(lib.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(link("libhibi.so"), Path::new(&format!("libhibi.so.{MAJOR}")));
    assert_eq!(link(&format!("libhibi.so.{MAJOR}")), Path::new(&format!("libhibi.so.{VERSION}")));
    let installed = std::fs::read(prefix.join("include/hibi.hpp")).unwrap();
    assert!(installed == std::fs::read(workspace_root().join("include/hibi.hpp")).unwrap());
}

/// The shared library names itself libhibi.so.MAJOR, so programs linked to it load any
/// later library of the same major version.
#[test]
fn shared_library_soname_is_the_major_version() {
    let dynamic = stdout(hibi_tests::tool("readelf").arg("-d").arg(prefix().join(format!("lib/libhibi.so.{VERSION}"))));
    let soname: Vec<&str> = dynamic.lines().filter(|l| l.contains("(SONAME)")).collect();
    assert_eq!(soname.len(), 1, "{dynamic}");
    assert!(soname[0].ends_with(&format!("Library soname: [libhibi.so.{MAJOR}]")), "{}", soname[0]);
}

/// `HIBI_VERSION_MAJOR/MINOR/PATCH` in the installed header are the package's version (the
/// C program checks them against `hibi_version()`, see the consumer tests).
#[test]
fn header_version_macros_are_the_package_version() {
    let header = std::fs::read_to_string(prefix().join("include/hibi.h")).unwrap();
    for (name, value) in [
        ("MAJOR", env!("CARGO_PKG_VERSION_MAJOR")),
        ("MINOR", env!("CARGO_PKG_VERSION_MINOR")),
        ("PATCH", env!("CARGO_PKG_VERSION_PATCH")),
    ] {
        let define = format!("#define HIBI_VERSION_{name} {value}");
        assert_eq!(header.lines().filter(|l| *l == define).count(), 1, "no `{define}` in the header");
    }
}

/// The global symbols a library defines, as `nm -g --defined-only` (`-D` for a shared one)
/// would list them, read with `readelf`: binutils' `nm` hands objects that carry LLVM
/// bitcode (`.llvmbc`, in cargo's release archive) to the system's LLVM plugin, which may be
/// older than rustc's LLVM and then reports "no symbols".
fn defined_globals(lib: &Path, dynamic: bool) -> Vec<String> {
    let mut readelf = hibi_tests::tool("readelf");
    readelf.arg("-W").arg(if dynamic { "--dyn-syms" } else { "--syms" });
    let mut names: Vec<String> = stdout(readelf.arg(lib))
        .lines()
        .filter_map(|l| {
            // Num: Value Size Type Bind Vis Ndx Name
            let fields: Vec<&str> = l.split_whitespace().collect();
            let global = fields.len() >= 8 && ["GLOBAL", "WEAK", "UNIQUE"].contains(&fields[4]) && fields[6] != "UND";
            global.then(|| fields[7].split('@').next().unwrap().to_owned())
        })
        .collect();
    names.sort();
    names.dedup();
    names
}

/// The installed static library defines only the hibi_* functions as globals (and the one
/// comdat signature the unwinder's personality reference is merged by), all of those that
/// cargo's archive defines; the shared library exports the same functions and nothing else.
#[test]
fn libraries_export_only_the_hibi_functions() {
    let prefix = prefix();
    let before = defined_globals(&built_dir().join("libhibi.a"), false);
    let api: Vec<String> = before.iter().filter(|s| s.starts_with("hibi_")).cloned().collect();
    assert!(api.len() >= 60 && api.contains(&"hibi_version".to_owned()), "{api:?}");
    assert!(before.len() > api.len(), "cargo's archive defines only hibi_*: nothing to hide?");
    let after = defined_globals(&prefix.join("lib/libhibi.a"), false);
    let others: Vec<&String> = after.iter().filter(|s| !s.starts_with("hibi_")).collect();
    assert_eq!(others, ["DW.ref.rust_eh_personality"], "globals other than hibi_* in the installed libhibi.a");
    assert_eq!(after.iter().filter(|s| s.starts_with("hibi_")).cloned().collect::<Vec<_>>(), api);
    let shared = defined_globals(&prefix.join(format!("lib/libhibi.so.{VERSION}")), true);
    assert_eq!(shared, api, "libhibi.so exports other symbols than the hibi_* functions");
    println!("global symbols defined: cargo's libhibi.a {}, installed libhibi.a {}", before.len(), after.len());
}

/// What tests/consumer/main.cpp prints.
fn check_consumer(output: &str) {
    let expected = format!(
        "hibi_version() {VERSION}, macros {VERSION}, equal: yes\nmud: cracks\nglass: fragments\n\
         skin: 1 cells, 4096 heights\nunknown preset: status 1093\n"
    );
    assert_eq!(output, expected);
}

/// The libhibi the program at `exe` needs at run time, if any (its DT_NEEDED entries).
fn needs_libhibi(exe: &Path) -> Option<String> {
    let dynamic = stdout(hibi_tests::tool("readelf").arg("-d").arg(exe));
    dynamic.lines().find(|l| l.contains("(NEEDED)") && l.contains("libhibi")).map(|l| {
        let start = l.find('[').unwrap() + 1;
        l[start..l.len() - 1].to_owned()
    })
}

fn pkg_config(args: &[&str]) -> Vec<String> {
    let pc = prefix().join("lib/pkgconfig");
    let output = stdout(hibi_tests::tool("pkg-config").args(args).arg("hibi").env("PKG_CONFIG_PATH", pc));
    output.split_whitespace().map(str::to_owned).collect()
}

fn cxx() -> String {
    std::env::var("CXX").unwrap_or_else(|_| "c++".into())
}

#[test]
fn consumer_builds_with_pkg_config_shared() {
    assert_eq!(pkg_config(&["--modversion"]), [VERSION]);
    let dir = scratch_dir("pkg-config-shared");
    let exe = dir.join("consumer");
    let libdir = pkg_config(&["--variable=libdir"]).concat();
    run(hibi_tests::tool(cxx())
        .args(["-std=c++17", "-Wall", "-Wextra", "-Wpedantic", "-Werror"])
        .args(pkg_config(&["--cflags"]))
        .arg(workspace_root().join("tests/consumer/main.cpp"))
        .args(pkg_config(&["--libs"]))
        .arg(format!("-Wl,-rpath,{libdir}"))
        .arg("-o")
        .arg(&exe));
    assert_eq!(needs_libhibi(&exe), Some(format!("libhibi.so.{MAJOR}")));
    check_consumer(&stdout(Command::new(&exe).env_remove("LD_LIBRARY_PATH")));
}

/// Builds tests/consumer/main.cpp against the installed libhibi.a through pkg-config, with
/// `flags` added, in a scratch directory `name`; returns the program.
fn consumer_static(name: &str, flags: &[&str]) -> PathBuf {
    let dir = scratch_dir(name);
    let exe = dir.join("consumer");
    let libdir = pkg_config(&["--variable=libdir"]).concat();
    // The archive by path (-lhibi would find the shared library first), then what
    // `--static` adds for it.
    let private: Vec<String> =
        pkg_config(&["--static", "--libs-only-l"]).into_iter().filter(|l| l != "-lhibi").collect();
    run(hibi_tests::tool(cxx())
        .args(["-std=c++17", "-Wall", "-Wextra", "-Wpedantic", "-Werror"])
        .args(flags)
        .args(pkg_config(&["--cflags"]))
        .arg(workspace_root().join("tests/consumer/main.cpp"))
        .arg(Path::new(&libdir).join("libhibi.a"))
        .args(private)
        .arg("-o")
        .arg(&exe));
    assert_eq!(needs_libhibi(&exe), None);
    exe
}

/// `program` under Valgrind (quiet, any error or leak a failing status).
fn valgrind(program: &Path) -> Command {
    let mut command = hibi_tests::tool(VALGRIND[0]);
    command.args(&VALGRIND[1..]).arg(program);
    command
}

/// `program`, built with [`SANITIZE_FLAGS`], with the sanitizers' options.
fn sanitized(program: &Path) -> Command {
    let mut command = Command::new(program);
    command.env(ASAN_OPTIONS.0, ASAN_OPTIONS.1);
    command
}

/// Runs `command`, which must succeed and print nothing on stderr (where the sanitizers and
/// Valgrind report); returns what it printed on stdout.
fn clean_stdout(command: &mut Command) -> String {
    let output = run(command);
    assert!(output.stderr.is_empty(), "{command:?} printed on stderr:\n{}", String::from_utf8_lossy(&output.stderr));
    String::from_utf8(output.stdout).expect("UTF-8 output")
}

#[test]
fn consumer_builds_with_pkg_config_static() {
    let exe = consumer_static("pkg-config-static", &[]);
    check_consumer(&stdout(&mut Command::new(&exe)));
}

/// The installed package's consumer, linked statically, under ASan (with LeakSanitizer) and
/// UBSan: no report, the same output.
#[test]
fn consumer_is_clean_under_sanitizers() {
    let exe = consumer_static("pkg-config-sanitized", SANITIZE_FLAGS);
    check_consumer(&clean_stdout(&mut sanitized(&exe)));
}

/// The installed package's consumer, linked statically, under Valgrind: no error, no leak,
/// the same output.
#[test]
fn consumer_is_clean_under_valgrind() {
    let exe = consumer_static("pkg-config-valgrind", &[]);
    check_consumer(&clean_stdout(&mut valgrind(&exe)));
}

/// The undefined symbols of a library (what it needs from elsewhere), read with `readelf`.
fn undefined_symbols(lib: &Path) -> Vec<String> {
    let mut names: Vec<String> = stdout(hibi_tests::tool("readelf").arg("-W").arg("--syms").arg(lib))
        .lines()
        .filter_map(|l| {
            let fields: Vec<&str> = l.split_whitespace().collect();
            (fields.len() >= 8 && fields[6] == "UND").then(|| fields[7].split('@').next().unwrap().to_owned())
        })
        .collect();
    names.sort();
    names.dedup();
    names
}

/// A fully static program (`c++ -static`, glibc's libc.a too) links the installed libhibi.a
/// without a word from the linker: `ffi/install`'s garbage-collected partial link dropped
/// the parts of std that reference glibc's getaddrinfo and getpwuid_r (which make glibc's
/// linker warn that a static program needs the shared libraries at run time). It runs and
/// prints what the other builds print.
#[test]
fn fully_static_program_links_without_warnings() {
    let installed = undefined_symbols(&prefix().join("lib/libhibi.a"));
    let cargo = undefined_symbols(&built_dir().join("libhibi.a"));
    for name in ["getaddrinfo", "getpwuid_r"] {
        assert!(cargo.iter().any(|s| s == name), "cargo's libhibi.a no longer references {name}: update the test");
        assert!(!installed.iter().any(|s| s == name), "the installed libhibi.a references {name}");
    }
    println!("undefined symbols: cargo's libhibi.a {}, installed libhibi.a {}", cargo.len(), installed.len());
    let dir = scratch_dir("fully-static");
    let exe = dir.join("consumer");
    let link = run(hibi_tests::tool(cxx())
        .args(["-static", "-std=c++17", "-Wall", "-Wextra", "-Wpedantic", "-Werror", "-I"])
        .arg(prefix().join("include"))
        .arg(workspace_root().join("tests/consumer/main.cpp"))
        .arg(prefix().join("lib/libhibi.a"))
        .arg("-lm")
        .arg("-o")
        .arg(&exe));
    let warnings = String::from_utf8_lossy(&link.stderr);
    assert!(link.stdout.is_empty() && warnings.is_empty(), "the -static link printed:\n{warnings}");
    let headers = stdout(hibi_tests::tool("readelf").arg("-lW").arg(&exe));
    assert!(!headers.contains("INTERP") && !headers.contains("DYNAMIC"), "not a static executable:\n{headers}");
    check_consumer(&clean_stdout(&mut Command::new(&exe)));
}

/// Configures and builds tests/consumer with CMake against the install; `extra` are more
/// `-D` settings. Returns the configure step's output when it fails, else the program.
fn cmake_consumer(name: &str, extra: &[&str]) -> Result<PathBuf, String> {
    let build = scratch_dir(name);
    let configure = hibi_tests::tool("cmake")
        .arg("-S")
        .arg(workspace_root().join("tests/consumer"))
        .arg("-B")
        .arg(&build)
        .arg(format!("-DCMAKE_PREFIX_PATH={}", prefix().display()))
        .arg(format!("-DCMAKE_CXX_COMPILER={}", cxx()))
        .args(extra)
        .output()
        .expect("run cmake (install it: .ci/run does)");
    if !configure.status.success() {
        return Err(String::from_utf8_lossy(&configure.stderr).into_owned());
    }
    run(hibi_tests::tool("cmake").arg("--build").arg(&build));
    Ok(build.join("consumer"))
}

#[test]
fn consumer_builds_with_cmake_shared() {
    let exe = cmake_consumer("cmake-shared", &[]).unwrap_or_else(|e| panic!("cmake configure failed:\n{e}"));
    assert_eq!(needs_libhibi(&exe), Some(format!("libhibi.so.{MAJOR}")));
    check_consumer(&stdout(Command::new(&exe).env_remove("LD_LIBRARY_PATH")));
}

#[test]
fn consumer_builds_with_cmake_static() {
    let exe = cmake_consumer("cmake-static", &["-DHIBI_STATIC=ON"])
        .unwrap_or_else(|e| panic!("cmake configure failed:\n{e}"));
    assert_eq!(needs_libhibi(&exe), None);
    check_consumer(&stdout(&mut Command::new(&exe)));
}

/// The CMake package refuses a request for another major version.
#[test]
fn cmake_package_refuses_another_major_version() {
    let next = MAJOR.parse::<u32>().unwrap() + 1;
    let error = cmake_consumer("cmake-next-major", &[&format!("-DHIBI_WANT={next}")])
        .expect_err("find_package accepted another major version");
    assert!(error.contains(&format!("version: {VERSION}")), "{error}");
}

/// Builds tests/second_rust_lib's libsecond.a, then its C program linked with it and the
/// installed libhibi.a in both orders, with `flags` added, in a scratch directory `name`;
/// returns each order's name and program.
fn second_rust_lib_programs(name: &str, flags: &[&str]) -> Vec<(&'static str, PathBuf)> {
    let root = workspace_root();
    let target = root.join("target/second-rust-lib");
    run(Command::new(env!("CARGO"))
        .args(["build", "--offline", "--quiet", "--manifest-path"])
        .arg(root.join("tests/second_rust_lib/Cargo.toml"))
        .arg("--target-dir")
        .arg(&target));
    let second = target.join("debug/libsecond.a");
    let dir = scratch_dir(name);
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    // Both orders: neither library's Rust symbols may satisfy or clash with the other's.
    [
        ("hibi_first", &prefix().join("lib/libhibi.a"), &second),
        ("second_first", &second, &prefix().join("lib/libhibi.a")),
    ]
    .into_iter()
    .map(|(order, first, then)| {
        let exe = dir.join(order);
        run(hibi_tests::tool(&cc)
            .args(["-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Werror"])
            .args(flags)
            .arg("-I")
            .arg(prefix().join("include"))
            .arg(root.join("tests/second_rust_lib/main.c"))
            .arg(first)
            .arg(then)
            .args(["-lpthread", "-ldl", "-lm"])
            .arg("-o")
            .arg(&exe));
        (order, exe)
    })
    .collect()
}

/// What tests/second_rust_lib/main.c prints: the second library's work (its thread and its
/// caught panic) and hibi's first draw for seed 42, stream 7.
fn check_second_rust_lib(order: &str, output: &str) {
    assert_eq!(
        output,
        format!("second_work(100): 5054\nsecond_work(0): 2\nhibi draw: {}\n", Rng::from_key(42, 7).next_u32()),
        "{order}"
    );
}

/// Link hygiene: one C program links the installed libhibi.a and a second Rust static
/// library (its own std, threads and a caught panic) and runs both.
#[test]
fn static_library_links_next_to_a_second_rust_static_library() {
    for (order, exe) in second_rust_lib_programs("second-rust-lib", &[]) {
        check_second_rust_lib(order, &clean_stdout(&mut Command::new(&exe)));
    }
}

/// The two Rust static libraries in one program, under ASan (with LeakSanitizer) and UBSan.
#[test]
fn second_rust_static_library_program_is_clean_under_sanitizers() {
    for (order, exe) in second_rust_lib_programs("second-rust-lib-sanitized", SANITIZE_FLAGS) {
        check_second_rust_lib(order, &clean_stdout(&mut sanitized(&exe)));
    }
}

/// The two Rust static libraries in one program, under Valgrind.
#[test]
fn second_rust_static_library_program_is_clean_under_valgrind() {
    for (order, exe) in second_rust_lib_programs("second-rust-lib-valgrind", &[]) {
        check_second_rust_lib(order, &clean_stdout(&mut valgrind(&exe)));
    }
}
