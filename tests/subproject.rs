//! hibi as a CMake subproject (the root `CMakeLists.txt`): a project (`tests/subproject/`)
//! takes it in through `add_subdirectory` and through `FetchContent` from a source archive of
//! the repository, with gcc and with clang, shared and static; its C and C++ programs build
//! against `hibi::hibi` and run. And hibi on its own, as the top-level project, builds its
//! examples and runs them with `ctest`.
//!
//! The CMake build type follows the test's profile: Debug in a debug run (cargo's dev
//! profile), Release in a release run (`--release`), so the test command covers both. cargo
//! builds in the C link tests' target directory (`target/c-link`, through the
//! `HIBI_CARGO_TARGET_DIR` option) to share what they compiled; the builds run one at a time
//! because they share it.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Mutex, OnceLock};

use hibi_tests::{run, stdout, workspace_root};

const MAJOR: &str = env!("CARGO_PKG_VERSION_MAJOR");
const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The CMake build type of this run and the cargo output directory it must use.
fn build_type() -> (&'static str, &'static str) {
    if cfg!(debug_assertions) { ("Debug", "debug") } else { ("Release", "release") }
}

/// One CMake build at a time: they share cargo's target directory and its output files.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// A fresh directory for one test's build.
fn scratch_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("subproject-{}-{name}", build_type().1));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create a build directory");
    dir
}

/// A source archive of the repository as it is checked out (the files git tracks or would
/// track, as they are in the work tree), `hibi-VERSION/` inside, and its SHA-256.
fn source_archive() -> &'static (PathBuf, String) {
    static ARCHIVE: OnceLock<(PathBuf, String)> = OnceLock::new();
    ARCHIVE.get_or_init(|| {
        let root = workspace_root();
        let listed = run(hibi_tests::tool("git")
            .args(["ls-files", "-z", "--cached", "--others", "--exclude-standard"])
            .current_dir(root))
        .stdout;
        let mut files: Vec<u8> = Vec::new();
        for name in listed.split(|&b| b == 0).filter(|n| !n.is_empty()) {
            // A tracked file deleted in the work tree is not part of it.
            if root.join(std::str::from_utf8(name).expect("UTF-8 path")).is_file() {
                files.extend_from_slice(name);
                files.push(0);
            }
        }
        let dir = scratch_dir("archive");
        let list = dir.join("files");
        std::fs::write(&list, files).unwrap();
        let archive = dir.join(format!("hibi-{VERSION}.tar.gz"));
        run(hibi_tests::tool("tar")
            .arg("-C")
            .arg(root)
            .args(["--null", "--files-from"])
            .arg(&list)
            .arg(format!("--transform=s,^,hibi-{VERSION}/,"))
            .arg("-czf")
            .arg(&archive));
        let sum = stdout(hibi_tests::tool("sha256sum").arg(&archive));
        (archive, sum.split_whitespace().next().expect("a SHA-256").to_owned())
    })
}

/// The C and C++ compilers of a compiler family.
fn compilers(family: &str) -> [&'static str; 2] {
    match family {
        "gcc" => ["gcc", "g++"],
        "clang" => ["clang", "clang++"],
        other => panic!("no compiler family {other}"),
    }
}

/// Configures and builds `source` in a fresh directory `name` with the compilers of `family`,
/// this run's build type, cargo's target directory shared, and `extra` settings; returns
/// the build directory.
fn cmake_build(name: &str, source: &Path, family: &str, extra: &[String]) -> PathBuf {
    let build = scratch_dir(name);
    let [cc, cxx] = compilers(family);
    run(hibi_tests::tool("cmake")
        .arg("-S")
        .arg(source)
        .arg("-B")
        .arg(&build)
        .arg(format!("-DCMAKE_BUILD_TYPE={}", build_type().0))
        .arg(format!("-DCMAKE_C_COMPILER={cc}"))
        .arg(format!("-DCMAKE_CXX_COMPILER={cxx}"))
        .arg(format!("-DHIBI_CARGO_TARGET_DIR={}", workspace_root().join("target/c-link").display()))
        .args(extra)
        // cargo as this test's cargo, whatever is on PATH.
        .arg(format!("-DHIBI_CARGO={}", env!("CARGO")))
        .env_remove("CARGO_TARGET_DIR"));
    run(hibi_tests::tool("cmake").arg("--build").arg(&build).arg("--parallel").arg("2"));
    build
}

/// The libhibi a program needs at run time, if any (its DT_NEEDED entries).
fn needs_libhibi(exe: &Path) -> Option<String> {
    let dynamic = stdout(hibi_tests::tool("readelf").arg("-d").arg(exe));
    dynamic.lines().find(|l| l.contains("(NEEDED)") && l.contains("libhibi")).map(|l| {
        let start = l.find('[').unwrap() + 1;
        l[start..l.len() - 1].to_owned()
    })
}

/// Builds tests/subproject taking hibi in `via` (`add_subdirectory` or `FetchContent`) with
/// `family`'s compilers and the `link` library, then checks hibi's build directory `hibi_build`
/// (relative to the consumer's) holds this build type's libraries only, and runs both programs.
fn consumer(via: &str, family: &str, link: &str) {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let mut extra = vec![format!("-DHIBI_VIA={via}"), format!("-DHIBI_LINK={link}")];
    let hibi_build = match via {
        "add_subdirectory" => {
            extra.push(format!("-DHIBI_SOURCE={}", workspace_root().display()));
            "hibi"
        }
        _ => {
            let (archive, sha256) = source_archive();
            extra.push(format!("-DHIBI_URL={}", archive.display()));
            extra.push(format!("-DHIBI_URL_SHA256={sha256}"));
            "_deps/hibi-build"
        }
    };
    let build =
        cmake_build(&format!("{via}-{family}-{link}"), &workspace_root().join("tests/subproject"), family, &extra);
    if via == "FetchContent" {
        let fetched = build.join("_deps/hibi-src/include/hibi.h");
        assert!(fetched.is_file(), "FetchContent did not unpack the archive: no {}", fetched.display());
    }
    // This build type's cargo profile, and only it.
    let libs = build.join(hibi_build).join("hibi-lib");
    let profiles: Vec<String> = std::fs::read_dir(&libs)
        .unwrap_or_else(|e| panic!("{}: {e}", libs.display()))
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert_eq!(profiles, [build_type().1], "cargo profiles built for {}", build_type().0);
    let lib = libs.join(build_type().1);
    assert_eq!(
        std::fs::read_link(lib.join(format!("libhibi.so.{MAJOR}"))).unwrap(),
        Path::new(&format!("libhibi.so.{VERSION}"))
    );
    for (exe, expected) in
        [("consumer_c", hibi_tests::consumer_c_output()), ("consumer_cpp", hibi_tests::consumer_cpp_output())]
    {
        let exe = build.join(exe);
        let needed = needs_libhibi(&exe);
        match link {
            "shared" => assert_eq!(needed, Some(format!("libhibi.so.{MAJOR}")), "{}", exe.display()),
            _ => assert_eq!(needed, None, "{} needs the shared library", exe.display()),
        }
        assert_eq!(stdout(Command::new(&exe).env_remove("LD_LIBRARY_PATH")), expected, "{}", exe.display());
    }
}

#[test]
fn add_subdirectory_gcc_shared() {
    consumer("add_subdirectory", "gcc", "shared");
}

#[test]
fn add_subdirectory_clang_static() {
    consumer("add_subdirectory", "clang", "static");
}

#[test]
fn fetch_content_gcc_static() {
    consumer("FetchContent", "gcc", "static");
}

#[test]
fn fetch_content_clang_shared() {
    consumer("FetchContent", "clang", "shared");
}

/// hibi as the top-level project builds every program in c_examples/ and `ctest` runs each.
#[test]
fn top_level_project_builds_and_runs_the_examples() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let build = cmake_build("top-level", workspace_root(), "gcc", &[]);
    let examples: Vec<String> = std::fs::read_dir(workspace_root().join("c_examples"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".c") || n.ends_with(".cpp"))
        .collect();
    assert!(examples.len() >= 5, "{examples:?}");
    let listed = stdout(hibi_tests::tool("ctest").arg("--show-only").current_dir(&build));
    let output = stdout(hibi_tests::tool("ctest").arg("--output-on-failure").current_dir(&build));
    for example in &examples {
        let test = format!("hibi_example_{}", example.replace('.', "_"));
        assert!(listed.contains(&format!(": {test}\n")), "no ctest test {test}:\n{listed}");
    }
    assert!(output.contains(&format!("100% tests passed, 0 tests failed out of {}", examples.len())), "{output}");
}

/// Every build type but Debug links cargo's release profile: RelWithDebInfo, MinSizeRel and
/// none, one after the other in one build directory (reconfigured), with gcc and the shared
/// library. Only the release run checks it (it needs the release profile's build).
#[test]
#[cfg_attr(debug_assertions, ignore = "links the release profile's library: the release run checks it")]
fn other_build_types_link_the_release_profile() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let source = format!("-DHIBI_SOURCE={}", workspace_root().display());
    let mut build = None;
    for build_type in ["RelWithDebInfo", "MinSizeRel", ""] {
        let settings =
            ["-DHIBI_VIA=add_subdirectory".to_owned(), source.clone(), format!("-DCMAKE_BUILD_TYPE={build_type}")];
        let dir = match &build {
            None => cmake_build("other-build-types", &workspace_root().join("tests/subproject"), "gcc", &settings),
            Some(dir) => {
                run(hibi_tests::tool("cmake").args(&settings).arg(dir));
                run(hibi_tests::tool("cmake").arg("--build").arg(dir).arg("--parallel").arg("2"));
                PathBuf::from(dir)
            }
        };
        let libs: Vec<String> = std::fs::read_dir(dir.join("hibi/hibi-lib"))
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        assert_eq!(libs, ["release"], "build type '{build_type}'");
        let exe = dir.join("consumer_c");
        let dynamic = stdout(hibi_tests::tool("readelf").arg("-d").arg(&exe));
        let runpath = dir.join("hibi/hibi-lib/release");
        assert!(dynamic.contains(&format!("[{}]", runpath.display())), "build type '{build_type}':\n{dynamic}");
        assert_eq!(stdout(Command::new(&exe).env_remove("LD_LIBRARY_PATH")), hibi_tests::consumer_c_output());
        build = Some(dir);
    }
}
