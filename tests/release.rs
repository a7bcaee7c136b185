//! The binary release archive (`ffi/release`): `hibi-VERSION-TARGET.tar.gz` and its SHA-256
//! file for the host, unpacked: its files, libraries without debug info (the shared one under
//! 1.5 MB), and programs built against it through its CMake package (`tests/consumer/`,
//! shared and static) and through pkg-config (`tests/consumer/main.c`), which run.
//!
//! The archive is always the release profile's, so only the test command's release run
//! makes it (in the C link tests' target directory, `target/c-link`, whose release build the
//! package tests share).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use hibi_tests::{run, stdout, workspace_root};

const MAJOR: &str = env!("CARGO_PKG_VERSION_MAJOR");
const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The most a stripped libhibi.so may weigh.
const SHARED_LIBRARY_LIMIT: u64 = 1_500_000;

/// A fresh directory for one test's files.
fn scratch_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("release-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create a directory");
    dir
}

/// The host's target triple, which the archive is named after.
fn host() -> String {
    let info = stdout(Command::new(std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into())).arg("-vV"));
    info.lines().find_map(|l| l.strip_prefix("host: ")).expect("rustc -vV names the host").to_owned()
}

struct Release {
    /// The directory ffi/release wrote into.
    out: PathBuf,
    /// The archive's name, without `.tar.gz`.
    name: String,
    /// The unpacked archive's top directory.
    unpacked: PathBuf,
}

/// Makes the release archive, once, and unpacks it.
fn release() -> &'static Release {
    static RELEASE: OnceLock<Release> = OnceLock::new();
    RELEASE.get_or_init(|| {
        let root = workspace_root();
        let out = scratch_dir("out");
        run(Command::new(root.join("ffi/release"))
            .arg("--out")
            .arg(&out)
            .arg("--target-dir")
            .arg(root.join("target/c-link"))
            .env("CARGO", env!("CARGO")));
        let name = format!("hibi-{VERSION}-{}", host());
        let unpack = scratch_dir("unpacked");
        run(hibi_tests::tool("tar").arg("-xzf").arg(out.join(format!("{name}.tar.gz"))).arg("-C").arg(&unpack));
        let unpacked = unpack.join(&name);
        Release { out, name, unpacked }
    })
}

/// Every path under `dir` that is not a directory, relative to it, sorted.
fn files_under(dir: &Path) -> Vec<String> {
    fn walk(base: &Path, dir: &Path, found: &mut Vec<String>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() && !path.is_symlink() {
                walk(base, &path, found);
            } else {
                found.push(path.strip_prefix(base).unwrap().to_string_lossy().into_owned());
            }
        }
    }
    let mut found = Vec::new();
    walk(dir, dir, &mut found);
    found.sort();
    found
}

/// The archive and its SHA-256 file are all ffi/release writes; `sha256sum -c` accepts the
/// pair; the archive holds one directory named like it, with the headers (the repository's),
/// the libraries and their links, the pkg-config and CMake files and the licences.
#[test]
#[cfg_attr(debug_assertions, ignore = "the release archive is the release profile's: the release run makes it")]
fn archive_holds_headers_libraries_package_files_and_licences() {
    let release = release();
    let archive = format!("{}.tar.gz", release.name);
    assert_eq!(files_under(&release.out), [archive.clone(), format!("{archive}.sha256")]);
    let check =
        stdout(hibi_tests::tool("sha256sum").arg("-c").arg(format!("{archive}.sha256")).current_dir(&release.out));
    assert_eq!(check, format!("{archive}: OK\n"));
    let mut expected = vec![
        "LICENSE-APACHE".to_owned(),
        "LICENSE-MIT".to_owned(),
        "include/hibi.h".to_owned(),
        "include/hibi.hpp".to_owned(),
        "lib/cmake/hibi/hibiConfig.cmake".to_owned(),
        "lib/cmake/hibi/hibiConfigVersion.cmake".to_owned(),
        "lib/libhibi.a".to_owned(),
        "lib/libhibi.so".to_owned(),
        format!("lib/libhibi.so.{MAJOR}"),
        format!("lib/libhibi.so.{VERSION}"),
        "lib/pkgconfig/hibi.pc".to_owned(),
    ];
    expected.sort();
    let top: Vec<String> = files_under(release.unpacked.parent().unwrap());
    assert!(top.iter().all(|f| f.starts_with(&format!("{}/", release.name))), "{top:?}");
    assert_eq!(files_under(&release.unpacked), expected);
    for (file, source) in [
        ("include/hibi.h", "include/hibi.h"),
        ("include/hibi.hpp", "include/hibi.hpp"),
        ("LICENSE-MIT", "LICENSE-MIT"),
        ("LICENSE-APACHE", "LICENSE-APACHE"),
    ] {
        assert!(
            std::fs::read(release.unpacked.join(file)).unwrap()
                == std::fs::read(workspace_root().join(source)).unwrap(),
            "{file} differs from the repository's"
        );
    }
    let lib = release.unpacked.join("lib");
    assert_eq!(std::fs::read_link(lib.join("libhibi.so")).unwrap(), Path::new(&format!("libhibi.so.{MAJOR}")));
    assert_eq!(
        std::fs::read_link(lib.join(format!("libhibi.so.{MAJOR}"))).unwrap(),
        Path::new(&format!("libhibi.so.{VERSION}"))
    );
}

/// The section names of an object file or archive (`readelf -SW`).
fn sections(file: &Path) -> Vec<String> {
    stdout(hibi_tests::tool("readelf").arg("-SW").arg(file))
        .lines()
        .filter_map(|l| {
            let l = l.trim_start();
            let rest = l.strip_prefix('[')?;
            let (_, after) = rest.split_once(']')?;
            after.split_whitespace().next().map(str::to_owned)
        })
        .collect()
}

/// The libraries carry no debug info (`.debug_*` sections) and keep their symbol tables;
/// cargo's carry debug info, so the check can tell. libhibi.so weighs less than 1.5 MB.
#[test]
#[cfg_attr(debug_assertions, ignore = "the release archive is the release profile's: the release run makes it")]
fn libraries_are_stripped_of_debug_info() {
    let lib = release().unpacked.join("lib");
    let cargo = workspace_root().join("target/c-link/release");
    for (shipped, built) in [
        (lib.join(format!("libhibi.so.{VERSION}")), cargo.join("libhibi.so")),
        (lib.join("libhibi.a"), cargo.join("libhibi.a")),
    ] {
        let debug = |file: &Path| sections(file).into_iter().filter(|s| s.starts_with(".debug_")).count();
        assert!(debug(&built) > 0, "cargo's {} has no debug info: the check cannot fail", built.display());
        assert_eq!(debug(&shipped), 0, "{} has debug sections", shipped.display());
        assert!(sections(&shipped).iter().any(|s| s == ".symtab"), "{} lost its symbol table", shipped.display());
        let name = shipped.file_name().unwrap().to_string_lossy();
        println!("{name}: {} bytes in the archive, {} bytes as cargo builds it", size(&shipped), size(&built));
    }
    let shared = size(&lib.join(format!("libhibi.so.{VERSION}")));
    assert!(shared < SHARED_LIBRARY_LIMIT, "libhibi.so is {shared} bytes, over {SHARED_LIBRARY_LIMIT}");
}

fn size(file: &Path) -> u64 {
    std::fs::metadata(file).unwrap().len()
}

/// The libhibi a program needs at run time, if any (its DT_NEEDED entries).
fn needs_libhibi(exe: &Path) -> Option<String> {
    let dynamic = stdout(hibi_tests::tool("readelf").arg("-d").arg(exe));
    dynamic.lines().find(|l| l.contains("(NEEDED)") && l.contains("libhibi")).map(|l| {
        let start = l.find('[').unwrap() + 1;
        l[start..l.len() - 1].to_owned()
    })
}

/// tests/consumer built with CMake against the unpacked archive (`find_package(hibi 0)`),
/// shared and static, runs and prints what it should.
#[test]
#[cfg_attr(debug_assertions, ignore = "the release archive is the release profile's: the release run makes it")]
fn cmake_consumer_builds_against_the_archive_and_runs() {
    for (link, extra) in [("shared", "-DHIBI_STATIC=OFF"), ("static", "-DHIBI_STATIC=ON")] {
        let build = scratch_dir(&format!("cmake-{link}"));
        run(hibi_tests::tool("cmake")
            .arg("-S")
            .arg(workspace_root().join("tests/consumer"))
            .arg("-B")
            .arg(&build)
            .arg(format!("-DCMAKE_PREFIX_PATH={}", release().unpacked.display()))
            .arg(extra));
        run(hibi_tests::tool("cmake").arg("--build").arg(&build));
        let exe = build.join("consumer");
        let expected = (link == "shared").then(|| format!("libhibi.so.{MAJOR}"));
        assert_eq!(needs_libhibi(&exe), expected, "{link}");
        assert_eq!(
            stdout(Command::new(&exe).env_remove("LD_LIBRARY_PATH")),
            hibi_tests::consumer_cpp_output(),
            "{link}"
        );
    }
}

/// tests/consumer/main.c built with `cc` and the archive's pkg-config file (shared, with an
/// rpath to its lib/), runs and prints what it should.
#[test]
#[cfg_attr(debug_assertions, ignore = "the release archive is the release profile's: the release run makes it")]
fn pkg_config_consumer_builds_against_the_archive_and_runs() {
    let pc = release().unpacked.join("lib/pkgconfig");
    let pkg_config = |args: &[&str]| -> Vec<String> {
        stdout(hibi_tests::tool("pkg-config").args(args).arg("hibi").env("PKG_CONFIG_PATH", &pc))
            .split_whitespace()
            .map(str::to_owned)
            .collect()
    };
    assert_eq!(pkg_config(&["--modversion"]), [VERSION]);
    let libdir = pkg_config(&["--variable=libdir"]).concat();
    let exe = scratch_dir("pkg-config").join("consumer");
    run(hibi_tests::tool(std::env::var("CC").unwrap_or_else(|_| "cc".into()))
        .args(["-std=c99", "-Wall", "-Wextra", "-Wpedantic", "-Werror"])
        .args(pkg_config(&["--cflags"]))
        .arg(workspace_root().join("tests/consumer/main.c"))
        .args(pkg_config(&["--libs"]))
        .arg(format!("-Wl,-rpath,{libdir}"))
        .arg("-o")
        .arg(&exe));
    assert_eq!(needs_libhibi(&exe), Some(format!("libhibi.so.{MAJOR}")));
    assert_eq!(stdout(Command::new(&exe).env_remove("LD_LIBRARY_PATH")), hibi_tests::consumer_c_output());
}
