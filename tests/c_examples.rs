//! The C99 and C++17 examples in `c_examples/` compile against `include/hibi.h` with
//! `-Wall -Wextra -Wpedantic -Werror`, link the static and the shared library the way an
//! engine does, run, and print exactly what hibi's Rust API computes. A third build links the
//! static library under AddressSanitizer, LeakSanitizer and UndefinedBehaviorSanitizer, a
//! fourth runs under Valgrind (`--error-exitcode=1 --leak-check=full`). The C regression
//! programs in `tests/c/` run under the sanitizers and under Valgrind; one of them,
//! `bad_input.c`, is the table in `docs/src/bad-input.md`, checked row by row against the header.
//! `tests/c/work_counts.c` also runs under Callgrind, which counts the instructions of create
//! and render calls with extreme float values, whose cost the sizes and capacities bound.
//! `tests/cpp/wrapper.cpp` checks the C++17 wrapper `include/hibi.hpp` against the C
//! calls, built by g++ and clang++, statically, shared, under the sanitizers and Valgrind;
//! `tests/cpp/results.cpp` checks its `hibi::Result` API, with exceptions, with
//! `-fno-exceptions -fno-rtti` and with `HIBI_NO_EXCEPTIONS`, as C++17 and C++20.

use std::path::{Path, PathBuf};
use std::process::Command;

use hibi_core::Rng;
use hibi_tests::{ASAN_OPTIONS, NATIVE_STATIC_LIBS, SANITIZE_FLAGS, VALGRIND, c_library_dir, workspace_root};

#[derive(Clone, Copy, Debug)]
enum Linkage {
    Static,
    Shared,
    /// Static, with `-fsanitize=address,undefined`; any report fails the run.
    Sanitized,
    /// Static, run under `valgrind --error-exitcode=1 --leak-check=full`; any error or leak
    /// fails the run.
    Valgrind,
    /// Static, run under Callgrind with collection off until the program turns it on; the
    /// counts go to [`callgrind_counts`].
    Callgrind,
    /// Static, run under Valgrind with its heap summary on stderr (any error fails the run).
    HeapCount,
}

/// The program `build_and_run_capturing` builds from `source` with `compiler` and `linkage`
/// (and a language standard other than the usual C99 or C++17 in the name: the wrapper is
/// also built as C++20; and the extra compiler flags, if any).
fn program_path(compiler: &str, standard: &str, source: &str, linkage: Linkage, flags: &[&str]) -> PathBuf {
    let stem = Path::new(source).file_name().unwrap().to_string_lossy().replace('.', "_");
    // Named by compiler too: the same source may be built by two compilers at once.
    let by = Path::new(compiler).file_name().unwrap().to_string_lossy().replace('+', "p");
    let std =
        if ["c99", "c++17"].contains(&standard) { String::new() } else { format!("_{}", standard.replace('+', "p")) };
    // And by its extra flags: one source may be built in several modes at once.
    let modes: String =
        flags.iter().map(|f| format!("_{}", f.trim_start_matches('-').replace(['-', '='], "_"))).collect();
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("{stem}_{by}_{linkage:?}{std}{modes}"))
}

/// Compiles `source` with `compiler` and the warning flags, links it to libhibi, runs it, and
/// returns what it printed.
fn build_and_run(compiler: &str, standard: &str, source: &str, linkage: Linkage) -> String {
    build_and_run_with(compiler, standard, source, linkage, &[])
}

/// As [`build_and_run`], passing `args` to the program.
fn build_and_run_with(compiler: &str, standard: &str, source: &str, linkage: Linkage, args: &[&str]) -> String {
    build_and_run_capturing(compiler, standard, source, linkage, args).0
}

/// As [`build_and_run_with`], returning what the program printed on stdout and on stderr.
fn build_and_run_capturing(
    compiler: &str,
    standard: &str,
    source: &str,
    linkage: Linkage,
    args: &[&str],
) -> (String, String) {
    build_and_run_flagged(compiler, standard, source, linkage, &[], args)
}

/// As [`build_and_run_capturing`], compiling with the extra `flags` (`-fno-exceptions`, a
/// `-D` define).
fn build_and_run_flagged(
    compiler: &str,
    standard: &str,
    source: &str,
    linkage: Linkage,
    flags: &[&str],
    args: &[&str],
) -> (String, String) {
    let root = workspace_root();
    let lib = c_library_dir();
    let exe = program_path(compiler, standard, source, linkage, flags);
    let mut cc = hibi_tests::tool(compiler);
    cc.arg(format!("-std={standard}"))
        .args(flags)
        .args(["-Wall", "-Wextra", "-Wpedantic", "-Werror", "-I"])
        .arg(root.join("include"))
        .arg(root.join(source))
        .arg("-o")
        .arg(&exe);
    match linkage {
        Linkage::Static | Linkage::Valgrind | Linkage::Callgrind | Linkage::HeapCount => {
            cc.arg(lib.join("libhibi.a")).args(NATIVE_STATIC_LIBS);
        }
        Linkage::Sanitized => {
            cc.args(SANITIZE_FLAGS).arg(lib.join("libhibi.a")).args(NATIVE_STATIC_LIBS);
        }
        Linkage::Shared => {
            cc.arg("-L").arg(lib).arg("-lhibi").arg(format!("-Wl,-rpath,{}", lib.display()));
        }
    }
    let compiled = cc.output().expect("run the C compiler");
    assert!(
        compiled.status.success(),
        "{compiler} {source} ({linkage:?} {flags:?}) failed:\n{}",
        String::from_utf8_lossy(&compiled.stderr)
    );
    // cargo points LD_LIBRARY_PATH at its own target directories, which may hold another
    // libhibi.so; the program must load the one it was linked with (its rpath).
    let mut command = match linkage {
        Linkage::Valgrind => {
            let mut valgrind = hibi_tests::tool(VALGRIND[0]);
            valgrind.args(&VALGRIND[1..]).arg(&exe);
            valgrind
        }
        Linkage::Callgrind => {
            for old in callgrind_dumps(&exe) {
                std::fs::remove_file(old).expect("remove an old Callgrind dump");
            }
            let mut callgrind = hibi_tests::tool("valgrind");
            callgrind
                .args(["-q", "--tool=callgrind", "--collect-atstart=no"])
                .arg(format!("--callgrind-out-file={}", exe.with_extension("callgrind").display()))
                .arg(&exe);
            callgrind
        }
        Linkage::HeapCount => {
            let mut valgrind = hibi_tests::tool("valgrind");
            valgrind.args(["--error-exitcode=1", "--leak-check=full"]).arg(&exe);
            valgrind
        }
        Linkage::Sanitized => {
            let mut sanitized = Command::new(&exe);
            sanitized.env(ASAN_OPTIONS.0, ASAN_OPTIONS.1);
            sanitized
        }
        Linkage::Static | Linkage::Shared => Command::new(&exe),
    };
    let run = command.args(args).env_remove("LD_LIBRARY_PATH").output().expect("run the example");
    let stdout = String::from_utf8(run.stdout).expect("UTF-8 output");
    let stderr = String::from_utf8_lossy(&run.stderr).into_owned();
    assert!(run.status.success(), "{source} ({linkage:?} {flags:?}) exited with {}:\n{stdout}\n{stderr}", run.status);
    (stdout, stderr)
}

/// What the examples must print for seed 42, stream 7, computed by the Rust API.
fn expected_draws() -> (String, String) {
    let mut rng = Rng::from_key(42, 7);
    let bits: Vec<String> = (0..4).map(|_| rng.next_u32().to_string()).collect();
    let uniform: Vec<String> = (0..3).map(|_| format!("{:.9}", f64::from(rng.uniform_f32()))).collect();
    (format!("next_u32: {}", bits.join(" ")), uniform.join(" "))
}

/// The uniform draws as printed by C's `%.9g`, reparsed so formatting differences vanish.
fn reparse_uniform(line: &str) -> String {
    line.trim_start_matches("uniform: ")
        .split(' ')
        .map(|v| format!("{:.9}", v.parse::<f64>().expect("a float")))
        .collect::<Vec<_>>()
        .join(" ")
}

fn line<'a>(output: &'a str, prefix: &str) -> &'a str {
    output.lines().find(|l| l.starts_with(prefix)).unwrap_or_else(|| panic!("no line {prefix:?} in:\n{output}"))
}

fn check_c_output(output: &str) {
    let (bits, uniform) = expected_draws();
    assert_eq!(line(output, "hibi "), format!("hibi {}", env!("CARGO_PKG_VERSION")));
    assert_eq!(line(output, "next_u32:"), bits);
    assert_eq!(reparse_uniform(line(output, "uniform:")), uniform);
    let mut rng = Rng::from_key(42, 7);
    for _ in 0..7 {
        rng.next_u32();
    }
    let poisson = rng.poisson(100.0).unwrap();
    assert_eq!(line(output, "poisson(100):"), format!("poisson(100): {poisson}"));
    assert_eq!(line(output, "rand(40"), "rand(40, 0.3, normal) within [28, 52]: yes");
    assert_eq!(
        line(output, "poisson(-1):"),
        "poisson(-1): status 256, poisson mean must be finite and within [0, 1e6]; output untouched: yes"
    );
    assert_eq!(line(output, "spread 9:"), "spread 9: status 4, an enumeration value is out of range");
    assert_eq!(line(output, "NULL rng:"), "NULL rng: status 1, a required pointer argument is NULL");
    assert_eq!(line(output, "short memory:"), "short memory: status 3, a buffer is smaller than the call needs");
    assert_eq!(
        line(output, "misaligned memory:"),
        "misaligned memory: status 2, a pointer argument is not aligned for its type"
    );
    assert_eq!(line(output, "caller memory"), "caller memory, same seed, same first draw: yes");
}

fn check_cpp_output(output: &str) {
    let (bits, uniform) = expected_draws();
    assert_eq!(line(output, "next_u32:"), bits);
    assert_eq!(reparse_uniform(line(output, "uniform:")), uniform);
    assert_eq!(line(output, "poisson(-1)"), "poisson(-1) threw: poisson mean must be finite and within [0, 1e6]");
    assert_eq!(line(output, "caller memory"), "caller memory, same seed, same first draw: yes");
}

fn c_compiler() -> String {
    std::env::var("CC").unwrap_or_else(|_| "cc".into())
}

fn cpp_compiler() -> String {
    std::env::var("CXX").unwrap_or_else(|_| "c++".into())
}

#[test]
fn c99_example_links_static_library() {
    check_c_output(&build_and_run(&c_compiler(), "c99", "c_examples/rng.c", Linkage::Static));
}

#[test]
fn c99_example_links_shared_library() {
    check_c_output(&build_and_run(&c_compiler(), "c99", "c_examples/rng.c", Linkage::Shared));
}

#[test]
fn c99_example_is_clean_under_sanitizers() {
    check_c_output(&build_and_run(&c_compiler(), "c99", "c_examples/rng.c", Linkage::Sanitized));
}

#[test]
fn c99_example_is_clean_under_valgrind() {
    check_c_output(&build_and_run(&c_compiler(), "c99", "c_examples/rng.c", Linkage::Valgrind));
}

#[test]
fn cpp17_example_is_clean_under_sanitizers() {
    check_cpp_output(&build_and_run(&cpp_compiler(), "c++17", "c_examples/rng.cpp", Linkage::Sanitized));
}

#[test]
fn cpp17_example_is_clean_under_valgrind() {
    check_cpp_output(&build_and_run(&cpp_compiler(), "c++17", "c_examples/rng.cpp", Linkage::Valgrind));
}

#[test]
fn cpp17_example_links_static_library() {
    check_cpp_output(&build_and_run(&cpp_compiler(), "c++17", "c_examples/rng.cpp", Linkage::Static));
}

#[test]
fn cpp17_example_links_shared_library() {
    check_cpp_output(&build_and_run(&cpp_compiler(), "c++17", "c_examples/rng.cpp", Linkage::Shared));
}

/// What the mud example computes, as Rust computes it for the same parameters: the mask,
/// the network's counts, and the cells' counts and summed ring area.
fn expected_mud() -> (Vec<u8>, hibi_core::mud::NetworkCounts, hibi_core::mud::CellCounts, f64) {
    use hibi_core::mud::{Mud, MudBuffers, MudLayers, MudParams, MudRender};
    let params = MudParams { columns: 96, rows: 96, seed: 7, ..MudParams::default() };
    let memory = params.memory().unwrap();
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let mut mud = Mud::new(&params, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
    mud.run().unwrap();
    let render = MudRender { width: 384, height: 384, ..MudRender::default() };
    let mut mask = vec![0u8; 384 * 384];
    mud.render(&render, MudLayers { mask: Some(&mut mask), ..Default::default() }).unwrap();
    let cells = mud.cell_counts();
    let (mut rings, mut points) =
        (vec![hibi_core::polygon::Ring::default(); cells.rings], vec![[0.0f32; 2]; cells.points]);
    mud.cells(&mut rings, &mut points).unwrap();
    // Summed in ring order, as the C program sums them.
    let area = rings.iter().fold(0.0f64, |sum, ring| sum + ring.area);
    (mask.iter().map(|v| 255 - v).collect(), mud.network_counts(), cells, area)
}

fn check_mud(linkage: Linkage) {
    let pgm = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("mud_{linkage:?}.pgm"));
    let output = build_and_run_with(&c_compiler(), "c99", "c_examples/mud.c", linkage, &[pgm.to_str().unwrap()]);
    assert_eq!(
        line(&output, "negative young_modulus:"),
        "negative young_modulus: status 522, mud: young_modulus (E) must be finite and > 0"
    );
    assert_eq!(
        line(&output, "params not from the default:"),
        "params not from the default: status 575, mud: the params struct did not come from hibi_mud_params_default or hibi_mud_params_preset"
    );
    assert!(line(&output, "finished:").starts_with("finished: shrink 0.0230"), "{output}");
    assert_eq!(
        line(&output, "short pixel buffer:"),
        "short pixel buffer: status 3, a buffer is smaller than the call needs"
    );
    let (mask, network, cells, area) = expected_mud();
    assert_eq!(
        line(&output, "network:"),
        format!("network: {} vertices, {} edges, {} points", network.vertices, network.edges, network.points)
    );
    assert_eq!(
        line(&output, "cells into a short buffer:"),
        "cells into a short buffer: status 3, a buffer is smaller than the call needs; nothing written: yes"
    );
    // The statistics line also starts "cells: "; this one names its rings.
    let cells_line = output
        .lines()
        .find(|l| l.starts_with("cells: ") && l.contains(" rings, "))
        .unwrap_or_else(|| panic!("no cells line with rings in:\n{output}"));
    assert_eq!(cells_line, format!("cells: {} rings, {} points, area {area:.1}", cells.rings, cells.points));
    assert_eq!(line(&output, "caller memory"), "caller memory, same bytes: yes");
    let bytes = std::fs::read(&pgm).expect("the example wrote its PGM");
    let header = b"P5\n384 384\n255\n";
    assert_eq!(&bytes[..header.len()], header);
    assert!(bytes[header.len()..] == mask[..], "the C program's picture differs from Rust's");
}

#[test]
fn mud_example_links_static_library() {
    check_mud(Linkage::Static);
}

#[test]
fn mud_example_links_shared_library() {
    check_mud(Linkage::Shared);
}

#[test]
fn mud_example_is_clean_under_sanitizers() {
    check_mud(Linkage::Sanitized);
}

#[test]
fn mud_example_is_clean_under_valgrind() {
    check_mud(Linkage::Valgrind);
}

/// The glass example's mask, as Rust draws it for the same parameters, and its fragment ring
/// and point counts.
fn expected_glass() -> (Vec<u8>, (usize, usize)) {
    use hibi_core::glass::{Glass, GlassLayers, GlassParams, GlassRender};

    let params = GlassParams { seed: 7, ..GlassParams::default() };
    let m = params.memory().unwrap();
    let mut memory = m.allocate();
    let buffers = memory.buffers();
    let mut glass = Glass::new(&params, buffers).unwrap();
    while !glass.step(100).finished {}
    let mut mask = vec![0u8; 640 * 640];
    glass.render(&GlassRender::default(), GlassLayers { mask: Some(&mut mask), ..Default::default() }).unwrap();
    (mask.iter().map(|v| 255 - v).collect(), glass.fragment_counts(&mut vec![0; m.scratch]).unwrap())
}

fn check_glass(linkage: Linkage) {
    let pgm = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("glass_{linkage:?}.pgm"));
    let output = build_and_run_with(&c_compiler(), "c99", "c_examples/glass.c", linkage, &[pgm.to_str().unwrap()]);
    assert_eq!(
        line(&output, "impact outside the plate:"),
        "impact outside the plate: status 1025, glass: impact must lie inside the plate"
    );
    let finished = line(&output, "finished after");
    let large: Vec<&str> = finished.split(", ").collect();
    assert!(
        large[1].ends_with("large")
            && large[2] == format!("{} of them at the edge", large[1].trim_end_matches(" large")),
        "{finished}"
    );
    assert_eq!(
        line(&output, "crack index past the end:"),
        "crack index past the end: status 1091, glass: crack index out of range"
    );
    let (mask, (rings, points)) = expected_glass();
    assert_eq!(
        line(&output, "fragments into a short buffer:"),
        "fragments into a short buffer: status 3, a buffer is smaller than the call needs"
    );
    assert_eq!(
        line(&output, "fragments:"),
        format!("fragments: {rings}, holes: 0, points: {points}, covering 409600.0 of 409600.0 square pixels")
    );
    assert!(line(&output, "second impact drew M").starts_with("second impact drew M "), "{output}");
    assert_eq!(line(&output, "caller memory"), "caller memory, same bytes: yes");
    let bytes = std::fs::read(&pgm).expect("the example wrote its PGM");
    let header = b"P5\n640 640\n255\n";
    assert_eq!(&bytes[..header.len()], header);
    assert!(bytes[header.len()..] == mask[..], "the C program's picture differs from Rust's");
}

#[test]
fn glass_example_links_static_library() {
    check_glass(Linkage::Static);
}

#[test]
fn glass_example_links_shared_library() {
    check_glass(Linkage::Shared);
}

#[test]
fn glass_example_is_clean_under_sanitizers() {
    check_glass(Linkage::Sanitized);
}

#[test]
fn glass_example_is_clean_under_valgrind() {
    check_glass(Linkage::Valgrind);
}

/// What the skin example computes, as Rust computes it for the same parameters: the shaded
/// preview, the cell count per level, and the cell (and its parent) that pixel (100, 100)
/// lies in at level 2.
fn expected_skin() -> (Vec<u8>, [usize; 3], (u32, u32)) {
    use hibi_core::skin::{ShadeParams, Skin, SkinLayers, SkinParams, SkinRender, preset, shade};

    let params = SkinParams { width: 200, height: 200, ..preset("fig19a").unwrap() };
    let m = params.memory().unwrap();
    let mut memory = m.allocate();
    let buffers = memory.buffers();
    let mut skin = Skin::<f32>::new(&params, buffers).unwrap();
    assert!(skin.run().finished);
    let pixels = 200 * 200;
    let (mut height, mut normal, mut map) = (vec![0.0f32; pixels], vec![[0.0f32; 3]; pixels], vec![0u32; pixels]);
    let layers = SkinLayers { height: Some(&mut height), normal: Some(&mut normal), ..SkinLayers::default() };
    skin.render(&SkinRender::default(), layers).unwrap();
    let mut rgb = vec![[0u8; 3]; pixels];
    shade(&height, &normal, &ShadeParams::default(), &mut rgb).unwrap();
    let layers = SkinLayers { cell: Some(&mut map), ..SkinLayers::default() };
    skin.render(&SkinRender { cell_level: 2, ..SkinRender::default() }, layers).unwrap();
    let mut per_level = [0; 3];
    for c in skin.cells() {
        per_level[c.level as usize] += 1;
    }
    let at = map[100 * 200 + 100];
    (rgb.concat(), per_level, (at, skin.cells()[at as usize].parent))
}

fn check_skin(linkage: Linkage) {
    let ppm = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("skin_{linkage:?}.ppm"));
    let output = build_and_run_with(&c_compiler(), "c99", "c_examples/skin.c", linkage, &[ppm.to_str().unwrap()]);
    assert_eq!(
        line(&output, "unknown preset fig99:"),
        "unknown preset fig99: status 1348, skin: no preset has that name"
    );
    assert_eq!(
        line(&output, "roundness 1.5 at level 1:"),
        "roundness 1.5 at level 1: status 1289, skin: a level's roundness must be in [0, 1]"
    );
    assert!(line(&output, "layout 7:").starts_with("layout 7: status 1344, skin: layout, jitter or periodic"));
    assert!(line(&output, "params not from the default:").starts_with("params not from the default: status 1343, "));
    let (rgb, per_level, (cell, parent)) = expected_skin();
    let total: usize = per_level.iter().sum();
    assert_eq!(
        line(&output, "cells:"),
        format!("cells: {total} (level 0: {}, level 1: {}, level 2: {})", per_level[0], per_level[1], per_level[2])
    );
    for level in 0..3 {
        let prefix = format!("level {level} outlines");
        assert_eq!(line(&output, &prefix), format!("{prefix} cover 40000.0 of 40000 square pixels"));
    }
    assert_eq!(
        line(&output, "cell index past the end:"),
        "cell index past the end: status 1349, skin: cell index out of range"
    );
    assert_eq!(
        line(&output, "outline into a short buffer:"),
        "outline into a short buffer: status 3, a buffer is smaller than the call needs"
    );
    assert_eq!(
        line(&output, "short normal buffer:"),
        "short normal buffer: status 3, a buffer is smaller than the call needs"
    );
    assert_eq!(
        line(&output, "cell map of level 3:"),
        "cell map of level 3: status 1346, skin: cell_level must be below levels"
    );
    assert_eq!(
        line(&output, "pixel (100, 100)"),
        format!("pixel (100, 100) lies in cell {cell} of level 2, its parent is cell {parent}")
    );
    assert_eq!(line(&output, "caller memory"), "caller memory, same bytes: yes");
    let bytes = std::fs::read(&ppm).expect("the example wrote its PPM");
    let header = b"P6\n200 200\n255\n";
    assert_eq!(&bytes[..header.len()], header);
    assert!(bytes[header.len()..] == rgb[..], "the C program's picture differs from Rust's");
}

#[test]
fn skin_example_links_static_library() {
    check_skin(Linkage::Static);
}

#[test]
fn skin_example_links_shared_library() {
    check_skin(Linkage::Shared);
}

#[test]
fn skin_example_is_clean_under_sanitizers() {
    check_skin(Linkage::Sanitized);
}

#[test]
fn skin_example_is_clean_under_valgrind() {
    check_skin(Linkage::Valgrind);
}

/// The C regression programs in `tests/c/`, statically linked under the sanitizers: what they
/// printed, after checking that they printed nothing on stderr.
fn regression(source: &str) -> String {
    let (stdout, stderr) = build_and_run_capturing(&c_compiler(), "c99", source, Linkage::Sanitized, &[]);
    assert!(stderr.is_empty(), "{source} printed on stderr:\n{stderr}");
    stdout
}

/// Every C program in `tests/c/`, with the path the tests run it by.
fn c_tests() -> Vec<String> {
    let dir = workspace_root().join("tests/c");
    let mut sources: Vec<String> = std::fs::read_dir(&dir)
        .expect("read tests/c")
        .map(|entry| entry.expect("a tests/c entry").file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".c"))
        .map(|name| format!("tests/c/{name}"))
        .collect();
    sources.sort();
    sources
}

/// Every C program in `tests/c/` runs clean under Valgrind: no error, no leak, nothing on
/// stderr. (What each prints is checked under the sanitizers by its own test; some time
/// themselves, which Valgrind's slowdown would spoil.)
#[test]
fn c_tests_are_clean_under_valgrind() {
    let sources = c_tests();
    assert!(sources.len() >= 5, "{sources:?}");
    for source in sources {
        let (stdout, stderr) = build_and_run_capturing(&c_compiler(), "c99", &source, Linkage::Valgrind, &[]);
        assert!(stderr.is_empty(), "{source} under Valgrind printed on stderr:\n{stderr}");
        assert!(!stdout.is_empty(), "{source} printed nothing");
    }
}

/// Every C program in `tests/c/` also runs clean when clang builds it under ASan and UBSan
/// (the tests above use the system's `cc`, usually gcc): exit 0, nothing on stderr.
#[test]
fn c_tests_are_clean_under_clang_sanitizers() {
    for source in c_tests() {
        let (stdout, stderr) = build_and_run_capturing("clang", "c99", &source, Linkage::Sanitized, &[]);
        assert!(stderr.is_empty(), "{source} built by clang printed on stderr:\n{stderr}");
        assert!(!stdout.is_empty(), "{source} printed nothing");
    }
}

/// The files Callgrind wrote for the program `exe` (its dumps and its final summary).
fn callgrind_dumps(exe: &Path) -> Vec<PathBuf> {
    let name = exe.with_extension("callgrind").file_name().unwrap().to_string_lossy().into_owned();
    std::fs::read_dir(exe.parent().unwrap())
        .expect("read the test's directory")
        .map(|entry| entry.expect("an entry").path())
        .filter(|path| path.file_name().unwrap().to_string_lossy().starts_with(&name))
        .collect()
}

/// The instructions each `CALLGRIND_DUMP_STATS_AT(name)` of the program `exe` counted, by
/// name.
fn callgrind_counts(exe: &Path) -> std::collections::BTreeMap<String, u64> {
    let mut counts = std::collections::BTreeMap::new();
    for dump in callgrind_dumps(exe) {
        let text = std::fs::read_to_string(&dump).expect("read a Callgrind dump");
        let Some(name) = text.lines().find_map(|l| l.strip_prefix("desc: Trigger: Client Request: ")) else {
            continue; // the summary at the program's end
        };
        let summary = text.lines().find_map(|l| l.strip_prefix("summary: ")).expect("a summary line");
        let count = summary.trim().parse().unwrap_or_else(|_| panic!("{}: summary {summary}", dump.display()));
        assert!(counts.insert(name.to_owned(), count).is_none(), "{name} dumped twice");
    }
    counts
}

/// Time bounded by sizes and capacities for the calls that report no work: each case of
/// `tests/c/work_counts.c` calls create or render with an extreme float value and, as its twin,
/// with a moderate value of the same sizes and capacities that already saturates what the value
/// can change; Callgrind counts each call's instructions. The extreme may cost at most `factor`
/// times its twin (plus 10,000 instructions), and where `same` the two results are equal (the
/// value cannot matter past the twin's). Two cases cost more: a glass `radial_mean` of 10000
/// (the most that is valid) is a Poisson draw of that mean, one uniform per unit of the mean
/// (Knuth's method), so creation is bounded by the validation's cap rather than by the
/// capacities (about 56 times the twin with mean 100); a mud `anisotropy_direction` of 1e30
/// costs libm's argument reduction of the huge angle in creation, a constant that weighs
/// against creation's own constant work (about 2 times the twin in release, 12 in debug). Two
/// cases are capacities, not floats: a glass plate created with `max_vertices` 2 000 000 costs
/// what one with 2 048 does (its vertex, edge and word arrays are not written), and one created
/// in caller memory (`hibi_glass_create_in`) with `max_cracks` 2 000 000 what one with 128 does
/// (its crack slots are not written either).
#[test]
fn c_create_and_render_work_does_not_grow_with_extreme_floats() {
    const CASES: &[(&str, f64, bool)] = &[
        ("glass-create ring_slope", 1.1, true),
        ("glass-create ring_offset", 1.1, true),
        ("glass-create large_slope", 1.1, true),
        ("glass-create ring_radius_slope", 1.1, true),
        ("glass-create speeds", 1.1, true),
        ("glass-create max_vertices", 1.1, true),
        ("glass-create radial_mean", 64.0, false),
        ("glass-create_in max_cracks", 1.1, true),
        ("mud-create break_stretch_mean", 1.1, false),
        ("mud-create anisotropy", 16.0, false),
        ("mud-create target_crack_density", 1.1, false),
        ("skin-create perturbation", 1.1, false),
        ("skin-create stretch", 1.1, false),
        ("mud-render min_width", 1.1, true),
        ("mud-render periodic min_width", 1.1, true),
        ("mud-render width_scale", 1.1, true),
        ("mud-render groove_depth", 1.1, false),
        ("mud-render height width_scale", 1.1, false),
        ("mud-render offset", 1.1, false),
        ("mud-render periodic offset", 1.1, false),
        ("glass-render line_width", 1.1, true),
        ("skin-render stretch", 1.1, false),
        ("skin-render periodic stretch", 1.1, false),
    ];
    let source = "tests/c/work_counts.c";
    let (stdout, stderr) = build_and_run_capturing(&c_compiler(), "c99", source, Linkage::Callgrind, &[]);
    assert!(stderr.is_empty(), "{source} under Callgrind printed on stderr:\n{stderr}");
    assert_eq!(line(&stdout, "glass-render cracks:"), "glass-render cracks: some");
    let counts = callgrind_counts(&program_path(&c_compiler(), "c99", source, Linkage::Callgrind, &[]));
    let names: Vec<String> =
        CASES.iter().flat_map(|(case, ..)| ["twin", "extreme"].map(|k| format!("{case} {k}"))).collect();
    assert_eq!(
        counts.keys().collect::<Vec<_>>(),
        names.iter().collect::<std::collections::BTreeSet<_>>().into_iter().collect::<Vec<_>>()
    );
    for &(case, factor, same) in CASES {
        let (twin, extreme) = (format!("{case} twin"), format!("{case} extreme"));
        let (t, e) = (counts[&twin], counts[&extreme]);
        // Callgrind counted the call (a program that never turned collection on counts 0).
        assert!(t > 1000 && e > 1000, "{case}: {t} and {e} instructions");
        assert!(e as f64 <= factor * t as f64 + 10_000.0, "{case}: {e} instructions, the twin {t} (factor {factor})");
        let result = |name: &str| line(&stdout, &format!("{name}:")).split_once(": ").unwrap().1.to_owned();
        assert_eq!(&result(&twin)[..8], "status 0", "{twin}");
        assert_eq!(&result(&extreme)[..8], "status 0", "{extreme}");
        if same {
            assert_eq!(result(&twin), result(&extreme), "{case}: the value changed the result past the twin's");
        }
        println!("{case}: twin {t}, extreme {e} instructions ({:.2}x)", e as f64 / t as f64);
    }
}

/// The program `tests/c/work_counts.c` (run under Callgrind above) prints every case's result.
#[test]
fn c_work_counts_prints_every_case() {
    let output = regression("tests/c/work_counts.c");
    assert_eq!(output.lines().filter(|l| l.contains(": status 0, digest ")).count(), 46, "{output}");
}

/// A huge ring count formula is bounded by `max_cracks`: creation takes under a second, not
/// minutes.
/// `tests/cpp/box2d.cpp`: the convex pieces of a glass plate's fragments and of a mud run's
/// cells become Box2D bodies (Debian's `libbox2d-dev`, Box2D 2.4, linked with `-lbox2d`),
/// one per fragment or cell, one fixture per piece; their masses at density 1 add up to the
/// plate's area within 10⁻⁴ (the slivers Box2D welds away, under 10⁻⁴ of it, left out), and
/// 120 steps of the world keep every position finite.
#[test]
fn cpp_pieces_become_box2d_bodies() {
    let root = workspace_root();
    let source = "tests/cpp/box2d.cpp";
    let exe = program_path("g++", "c++17", source, Linkage::Static, &["-lbox2d"]);
    let mut cc = hibi_tests::tool("g++");
    cc.args(["-std=c++17", "-Wall", "-Wextra", "-Wpedantic", "-Werror", "-I"])
        .arg(root.join("include"))
        .arg(root.join(source))
        .arg("-o")
        .arg(&exe)
        .arg(c_library_dir().join("libhibi.a"))
        .arg("-lbox2d")
        .args(NATIVE_STATIC_LIBS);
    let compiled = cc.output().expect("run g++");
    assert!(compiled.status.success(), "g++ {source} failed:\n{}", String::from_utf8_lossy(&compiled.stderr));
    let run = Command::new(&exe).env_remove("LD_LIBRARY_PATH").output().expect("run the Box2D test");
    let stdout = String::from_utf8(run.stdout).expect("UTF-8 output");
    assert!(run.status.success(), "{source}: {}\n{stdout}{}", run.status, String::from_utf8_lossy(&run.stderr));
    for model in ["glass", "mud"] {
        let l = line(&stdout, &format!("{model}:"));
        let bodies: Vec<&str> = l.split_whitespace().collect();
        assert_eq!(bodies[1], bodies[4], "a body per fragment: {l}");
        assert!(l.ends_with("120 steps: positions finite: yes, fell: yes"), "{l}");
        let ratio: f64 = l.split("masses / plate area = ").nth(1).unwrap().split(',').next().unwrap().parse().unwrap();
        assert!((ratio - 1.0).abs() <= 1e-4, "{l}");
    }
    println!("{stdout}");
}

/// Glass fragments and mud cells as triangles and convex pieces through the C API: each
/// polygon's pieces add up to its area, the plate's to its size, every piece counter-clockwise
/// and strictly convex with at most 8 points; a short buffer is refused by name, untouched.
#[test]
fn c_pieces_add_up_to_the_plate() {
    let output = regression("tests/c/pieces.c");
    for model in ["glass", "mud"] {
        let l = line(&output, &format!("{model}:"));
        assert!(l.contains("pieces add up: yes") && l.ends_with("all counter-clockwise and convex: yes"), "{l}");
        assert!(l.contains("of at most 8 points") || l.contains("of at most 7 points"), "{l}");
    }
}

#[test]
fn c_glass_create_is_bounded_by_the_capacities() {
    let output = regression("tests/c/glass_ring_counts.c");
    for field in ["ring_slope 100000", "ring_slope 1e+07", "ring_slope 1e+30", "ring_offset 1e+30"] {
        assert_eq!(
            line(&output, &format!("{field}:")),
            format!("{field}: create 0, under a second: yes, step 1090, crack count 0, cracks within max_cracks: yes")
        );
    }
}

/// Out of capacity, every output still works, and no panic message reaches stderr.
#[test]
fn c_glass_plate_out_of_capacity_stays_usable() {
    let output = regression("tests/c/glass_capacity.c");
    let plates: Vec<&str> = output.lines().filter(|l| l.starts_with("max_vertices ")).collect();
    assert_eq!(plates.len(), 12, "{output}");
    for plate in plates {
        let (_, results) = plate.split_once(": ").unwrap();
        assert_eq!(
            results, "step 1090 then 1090, fragment_counts 0, fragments 0 covering 409600.0, cracks 0, render 0",
            "{plate}"
        );
    }
}

/// `shrink_ratio` 1 is refused by name; an unreachable `break_stretch_mean` ends both solvers
/// alike: at the target shrink, uncracked, at a positive time.
#[test]
fn c_mud_solvers_agree_on_the_ends_of_the_shrink_range() {
    let output = regression("tests/c/mud_shrink.c");
    assert_eq!(
        line(&output, "shrink_ratio 1:"),
        "shrink_ratio 1: status 518, mud: shrink_ratio (gamma) must be >= FLT_MIN and < 1 (1 would never shrink); with \
         the growth drive, 1/gamma - 1 <= 100; \
         nothing created: yes"
    );
    assert_eq!(
        line(&output, "shrink_ratio 1, memory size:"),
        "shrink_ratio 1, memory size: status 518, size untouched: yes"
    );
    assert_eq!(line(&output, "shrink_ratio just below 1:"), "shrink_ratio just below 1: status 0");
    for solver in ["explicit", "quasi-static"] {
        let prefix = format!("{solver}, break_stretch_mean 1e30:");
        assert_eq!(
            line(&output, &prefix),
            format!("{prefix} status 0, finished 1, shrink 0.023, broken 0, positive time: yes")
        );
    }
}

/// Refusals name the field or argument the caller wrote, and the `*_written` counts are
/// required everywhere while the optional outputs are skipped.
#[test]
fn c_refusals_name_what_the_caller_wrote() {
    let output = regression("tests/c/messages.c");
    let expected = [
        "young_modulus 1e20: status 532, mud: (shear_modulus / young_modulus) * (element_size / layer_thickness)^2 \
         must be within [1e-6, 1e6] []",
        "damping_factor 1e9: status 534, mud: damping_factor is out of scale: 2 * sqrt(k_max * m) * damping_factor \
         must be within [1e-6, 1e6] []",
        "short_step 1e9: status 535, mud: short_step / (element_size * sqrt(density / young_modulus)) must be \
         within [1e-6, 1e6] []",
        "displacement_tolerance 1e-12: status 536, mud: displacement_tolerance is out of scale: k_min * \
         displacement_tolerance / element_size must be within [1e-6, 1e6] []",
        "stiffness_anisotropy_ratio 1e9: status 528, mud: stiffness_anisotropy_ratio must be within [1, 1e6] []",
        "glass layer 7: status 1094, hibi_glass_render: layer is not HIBI_GLASS_LAYER_MASK or HIBI_GLASS_LAYER_TIME []",
        "light (0, 0, 1e30): status 0, ok []",
        "light (0, 0, 0): status 1347, skin: the shading light direction must be three finite numbers, not all zero []",
        "shade without params: status 1, a required pointer argument is NULL [params]",
        "shade into NULL rgb: status 1, a required pointer argument is NULL [rgb]",
        "fragment_counts with NULL points: status 1, a required pointer argument is NULL [points]",
        "fragment_counts with NULL scratch: status 1, a required pointer argument is NULL [scratch]",
        "fragment_counts with a 1-byte scratch: status 3, a buffer is smaller than the call needs [scratch]",
        "a call that succeeds clears the name: status 0, ok []",
        "glass points with NULL written: status 1, a required pointer argument is NULL [written]",
        "glass step with NULL progress: status 0, ok []",
        "glass step on a NULL plate: status 1, a required pointer argument is NULL [glass]",
        "glass impact with NULL counts: status 0, ok []",
        "mud step with NULL progress: status 0, ok []",
        "mud step: status 0, ok []",
        "mud segments with NULL written: status 1, a required pointer argument is NULL [written]",
        "mud segments into NULL with a length: status 1, a required pointer argument is NULL [segments]",
        "mud create with NULL out: status 1, a required pointer argument is NULL [out]",
        "mud create_in with NULL memory: status 1, a required pointer argument is NULL [memory]",
    ];
    for want in expected {
        let (prefix, _) = want.split_once(": status").unwrap();
        assert_eq!(line(&output, &format!("{prefix}: ")), want);
    }
}

/// The status constants `include/hibi.h` declares (`HIBI_OK` and every `HIBI_ERROR_*`), by
/// name.
fn header_statuses() -> Vec<(String, u32)> {
    let header = std::fs::read_to_string(workspace_root().join("include/hibi.h")).expect("read include/hibi.h");
    let statuses: Vec<(String, u32)> = header
        .lines()
        .filter_map(|l| l.strip_prefix("#define "))
        .filter(|l| l.starts_with("HIBI_OK ") || l.starts_with("HIBI_ERROR_"))
        .map(|l| {
            let (name, value) = l.split_once(' ').unwrap_or_else(|| panic!("#define {l}"));
            (name.to_owned(), value.trim().parse().unwrap_or_else(|_| panic!("#define {l}: not a number")))
        })
        .collect();
    assert!(statuses.iter().any(|(name, _)| name == "HIBI_OK"), "no HIBI_OK in the header");
    statuses
}

/// The rows of `docs/src/bad-input.md`: (row, status constant) for each case, and the constants
/// listed as unreachable.
fn bad_input_table() -> (Vec<(String, String)>, Vec<String>) {
    let doc =
        std::fs::read_to_string(workspace_root().join("docs/src/bad-input.md")).expect("read docs/src/bad-input.md");
    let (mut rows, mut unreachable) = (Vec::new(), Vec::new());
    for l in doc.lines().filter(|l| l.starts_with("| `")) {
        let cells: Vec<&str> = l.trim_matches('|').split(" | ").map(str::trim).collect();
        let code = |cell: &str| cell.trim_matches('`').to_owned();
        if cells[0].starts_with("`HIBI_") {
            unreachable.push(code(cells[0]));
        } else {
            assert_eq!(cells.len(), 4, "a row has four cells: {l}");
            rows.push((code(cells[0]), code(cells[3])));
        }
    }
    (rows, unreachable)
}

/// Each row of docs/src/bad-input.md gets the status it names from
/// tests/c/bad_input.c (run under the sanitizers), no failing call wrote its output, the
/// program has no case the table lacks, and every status the header declares is reached by
/// a row or listed as unreachable (and then reached by none).
#[test]
fn c_bad_input_table() {
    let statuses = header_statuses();
    let value = |name: &str| {
        statuses
            .iter()
            .find(|(n, _)| n == name)
            .unwrap_or_else(|| panic!("docs/src/bad-input.md names {name}, which include/hibi.h does not declare"))
            .1
    };
    let (rows, unreachable) = bad_input_table();
    assert!(rows.len() >= statuses.len(), "{} rows", rows.len());
    let output = regression("tests/c/bad_input.c");
    let mut got = std::collections::BTreeMap::new();
    let mut unnamed = Vec::new();
    for l in output.lines() {
        let (row, rest) = l.split_once(": status ").unwrap_or_else(|| panic!("not a row: {l:?}"));
        let (rest, argument) = rest.rsplit_once(" [").unwrap_or_else(|| panic!("no argument: {l:?}"));
        let argument = argument.strip_suffix(']').unwrap_or_else(|| panic!("no argument: {l:?}"));
        let (status, outcome) = rest.split_once(", ").unwrap_or((rest, ""));
        let status: u32 = status.parse().unwrap_or_else(|_| panic!("not a status: {l:?}"));
        // A refusal about the call names what the caller wrote: the argument (a parameter
        // error's status names its field itself). Out of memory and a caught panic name none.
        let about_an_argument = (1..256).contains(&status) && ![5, 7].contains(&status);
        if about_an_argument && argument.is_empty() {
            unnamed.push(format!("{row} (status {status})"));
        }
        assert!(
            ["", "output untouched: yes", "output written: yes"].contains(&outcome),
            "{row}: {outcome} (a failing call must leave its output alone)"
        );
        assert!(got.insert(row.to_owned(), status).is_none(), "row {row} printed twice");
    }
    let mut seen = std::collections::BTreeSet::new();
    for (row, constant) in &rows {
        assert!(seen.insert(row), "row {row} is in the table twice");
        let status = *got.get(row).unwrap_or_else(|| panic!("row {row}: tests/c/bad_input.c has no such case"));
        assert_eq!(status, value(constant), "row {row}: status {status}, the table says {constant}");
    }
    assert!(unnamed.is_empty(), "refusals that hibi_error_argument() does not name: {unnamed:?}");
    let undocumented: Vec<&String> = got.keys().filter(|row| !seen.contains(row)).collect();
    assert!(undocumented.is_empty(), "cases not in docs/src/bad-input.md: {undocumented:?}");
    let reached: std::collections::BTreeSet<u32> = got.values().copied().collect();
    let missing: Vec<&str> = statuses
        .iter()
        .filter(|(name, v)| !reached.contains(v) && !unreachable.contains(name))
        .map(|(name, _)| name.as_str())
        .collect();
    assert!(missing.is_empty(), "statuses no C test reaches and the table does not call unreachable: {missing:?}");
    for name in &unreachable {
        assert!(!reached.contains(&value(name)), "{name} is listed as unreachable but a row reaches it");
    }
}

/// Every C program in `tests/c/` has a test that runs it under the sanitizers.
#[test]
fn every_c_test_runs_under_the_sanitizers() {
    let this = include_str!("c_examples.rs");
    for source in c_tests() {
        assert!(this.contains(&format!("regression(\"{source}\")")), "no test runs {source} under the sanitizers");
    }
}

/// What `tests/cpp/wrapper.cpp` (the C++17 wrapper `include/hibi.hpp`) must print: every
/// comparison of the wrapper with the C calls holds, errors carry the C status, message and
/// argument, renders of one object from four threads equal the lone render, every output
/// written through a `hibi::Span` view is the C call's, a view one element short throws
/// status 3 (`HIBI_ERROR_BUFFER_TOO_SMALL`) with nothing written, and built as `standard`
/// C++20, `std::span`s convert to views.
fn check_wrapper(output: &str, standard: &str) {
    let version = format!("hibi {}", env!("CARGO_PKG_VERSION"));
    assert_eq!(line(output, "hibi "), version);
    assert_eq!(line(output, "macros "), version.replace("hibi", "macros"));
    let expected = [
        "negative young_modulus: status 522, mud: young_modulus (E) must be finite and > 0, argument \"\", \
         same message as C: yes",
        "preset fig99: status 1348",
        "misaligned memory: status 2, argument \"memory\"",
        "short memory: status 3, a buffer is smaller than the call needs",
        "mud finished: yes, in more than one step: yes",
        "mud segments: yes",
        "mud network matches its counts: yes",
        "mud builds in ranges: same as network and cells: yes, steps: yes",
        "mud statistics as from C: yes",
        "mud mask as from C: yes",
        "mud height and time layers: yes",
        "mud short pixels: status 3",
        "mud views as from C: segments yes, network yes, cells yes, mask yes, height yes, time yes, longer yes",
        "mud short views: segments 3, network 3, cells 3, mask 3, height 3, time 3, untouched yes",
        "mud caller memory, same mask: yes",
        "glass: yes, every crack has points: yes",
        "glass crack past the end: status 1091",
        "glass from four threads equals the lone result: yes",
        "glass views as from C: points yes, fragments yes, mask yes, time yes",
        "glass short views: points 3, fragments 3, mask 3, time 3, untouched yes",
        "glass caller memory, same mask: yes",
        "glass second impact: yes",
        "skin built: yes, cells yes",
        "skin renders from four threads equal the lone render: yes",
        "skin views as from C: outline yes, height yes, normal yes, cells yes, shade yes",
        "skin short views: outline 3, height 3, normal 3, cells 3, shade 3, untouched yes",
        "skin cell map of level 9: status 1346",
        "skin caller memory, same preview: yes",
        "rng caller memory, same draws: yes",
        "rng views as from C: uniform yes, normal yes",
        if standard == "c++20" { "std::span views: yes" } else { "std::span views: not C++20" },
    ];
    for want in expected {
        let (prefix, _) = want.split_once(": ").unwrap();
        assert_eq!(line(output, &format!("{prefix}: ")), want);
    }
    assert!(line(output, "mud cells: ").starts_with("mud cells: some rings, area "), "{output}");
    assert!(line(output, "glass fragments").starts_with("glass fragments match their counts: yes, area 40000.0"));
    assert_eq!(
        line(output, "glass fragment build"),
        "glass fragment build in ranges: same as fragments: yes, steps: yes"
    );
    assert_eq!(output.lines().count(), expected.len() + 5, "{output}");
}

#[test]
fn cpp_wrapper_links_static_library_with_gxx() {
    check_wrapper(&build_and_run("g++", "c++17", "tests/cpp/wrapper.cpp", Linkage::Static), "c++17");
}

#[test]
fn cpp_wrapper_links_static_library_with_clangxx() {
    check_wrapper(&build_and_run("clang++", "c++17", "tests/cpp/wrapper.cpp", Linkage::Static), "c++17");
}

/// The wrapper is C++17, and builds as C++20 too, where `std::span` converts to its views.
#[test]
fn cpp_wrapper_builds_as_cpp20_with_gxx_and_clangxx() {
    for compiler in ["g++", "clang++"] {
        check_wrapper(&build_and_run(compiler, "c++20", "tests/cpp/wrapper.cpp", Linkage::Static), "c++20");
    }
}

#[test]
fn cpp_wrapper_links_shared_library() {
    check_wrapper(&build_and_run(&cpp_compiler(), "c++17", "tests/cpp/wrapper.cpp", Linkage::Shared), "c++17");
}

#[test]
fn cpp_wrapper_is_clean_under_sanitizers_with_gxx_and_clangxx() {
    for compiler in ["g++", "clang++"] {
        let (stdout, stderr) =
            build_and_run_capturing(compiler, "c++17", "tests/cpp/wrapper.cpp", Linkage::Sanitized, &[]);
        assert!(stderr.is_empty(), "{compiler}: stderr:\n{stderr}");
        check_wrapper(&stdout, "c++17");
    }
}

#[test]
fn cpp_wrapper_is_clean_under_valgrind() {
    let (stdout, stderr) = build_and_run_capturing("g++", "c++17", "tests/cpp/wrapper.cpp", Linkage::Valgrind, &[]);
    assert!(stderr.is_empty(), "stderr under Valgrind:\n{stderr}");
    check_wrapper(&stdout, "c++17");
}

/// The modes `tests/cpp/results.cpp` is built in: with exceptions (the `try_` twins beside
/// the throwing calls), without (`-fno-exceptions`, and `-fno-rtti` with it), and with
/// exceptions on but `HIBI_NO_EXCEPTIONS` defined; in the last two every call returns its
/// `hibi::Result`.
const WITH_EXCEPTIONS: &[&str] = &[];
const NO_EXCEPTIONS: &[&str] = &["-fno-exceptions", "-fno-rtti"];
const HIBI_NO_EXCEPTIONS: &[&str] = &["-DHIBI_NO_EXCEPTIONS"];

/// What `tests/cpp/results.cpp` must print, built with `flags` as `standard`: every entry
/// point's result equals the C call's and a failed call wrote nothing ("yes"), and each
/// failure carries the C status and the refused argument's name (views one element short:
/// status 3, `HIBI_ERROR_BUFFER_TOO_SMALL`; objects without a handle: status 1 and the
/// handle's name). Without exceptions a `hibi::Buffer` that cannot be allocated is empty,
/// which the C call refuses; with them, reading a failed result's value throws `hibi::Error`.
fn check_results(output: &str, flags: &[&str], standard: &str) {
    let results = flags != WITH_EXCEPTIONS;
    let mode = match flags {
        WITH_EXCEPTIONS => "exceptions, language exceptions on, rtti on",
        NO_EXCEPTIONS => "results, language exceptions off, rtti off",
        _ => "results, language exceptions on, rtti on",
    };
    let mut expected = vec![
        format!("mode: {mode}"),
        "try_check: yes; status 1 [rng]".into(),
        "value_or: yes; status 1 [mud]".into(),
        if results {
            "buffer of 2^62 bytes: yes; status 1 [memory]".into()
        } else {
            "value of a failure: throws hibi::Error: yes".into()
        },
    ];
    let lines = [
        "rng try_create_in, misaligned: yes; status 2 [memory]",
        "rng try_create_in, short: yes; status 3 [memory]",
        "rng try_create, try_next_u32: yes; status 1 [rng]",
        "rng try_uniform(view): yes; status 1 [values]",
        "rng try_uniform(n): yes; status 1 [rng]",
        "rng try_normal(view): yes; status 1 [rng]",
        "rng try_normal(n): yes; status 1 [rng]",
        "rng try_poisson: yes; status 256 []",
        "rng try_rand: yes; status 4 [spread]",
        "mud try_preset: yes; status 577 []",
        "mud try_memory_size: yes; status 522 []",
        "mud try_create: yes; status 522 []",
        "mud try_create_in: yes; status 3 [memory]",
        "mud try_step: yes; status 1 [mud]",
        "mud try_run: yes; status 1 [mud]",
        "mud try_segment_count: yes; status 1 [mud]",
        "mud try_segments(view): yes; status 3 [segments]",
        "mud try_segments(): yes; status 1 [mud]",
        "mud try_statistics: yes; status 1 [mud]",
        "mud try_network_counts: yes; status 1 [mud]",
        "mud try_network(views): yes; status 3 [edges]",
        "mud try_network(): yes; status 1 [mud]",
        "mud try_cell_counts: yes; status 1 [mud]",
        "mud try_cells(views): yes; status 3 [rings]",
        "mud try_cells(): yes; status 1 [mud]",
        "mud try_render: yes; status 773 []",
        "mud try_render_mask(view): yes; status 3 [pixels]",
        "mud try_render_height(view): yes; status 3 [pixels]",
        "mud try_render_time(view): yes; status 3 [pixels]",
        "mud try_render_mask(): yes; status 1 [mud]",
        "mud try_render_height(): yes; status 1 [mud]",
        "mud try_render_time(): yes; status 1 [mud]",
        "mud caller memory, same mask: yes",
        "mud try_render_layers: yes; status 775 [layers.cell]",
        "glass try_preset: yes; status 1093 []",
        "glass try_memory_size: yes; status 1024 []",
        "glass try_create: yes; status 1025 []",
        "glass try_create_in: yes; status 3 [memory]",
        "glass try_step: yes; status 1 [glass]",
        "glass try_run: yes; status 1 [glass]",
        "glass try_crack_count: yes; status 1 [glass]",
        "glass try_crack: yes; status 1091 []",
        "glass try_points(view): yes; status 3 [points]",
        "glass try_points(): yes; status 1091 []",
        "glass try_scratch_size: yes; status 1 [glass]",
        "glass try_scratch: yes; status 1 [glass]",
        "glass try_fragment_counts: yes; status 3 [scratch]",
        "glass try_fragments(views): yes; status 3 [points]",
        "glass try_fragments(): yes; status 1 [scratch]",
        "pieces try_pieces_scratch_size: yes; status 1536 []",
        "pieces try_piece_counts: yes; status 3 [scratch]",
        "pieces try_triangulate(views): yes; status 3 [triangles]",
        "pieces try_triangulate(): yes; status 1536 []",
        "pieces try_convex_pieces(views): yes; status 3 [pieces]",
        "pieces try_convex_pieces(): yes; status 1536 []",
        "glass try_render: yes; status 1094 []",
        "glass try_render_mask(view): yes; status 3 [pixels]",
        "glass try_render_time(view): yes; status 3 [pixels]",
        "glass try_render_mask(): yes; status 1 [glass]",
        "glass try_render_time(): yes; status 1 [glass]",
        "glass try_render_layers: yes; status 775 [layers.cell]",
        "glass try_impact: yes; status 1089 []",
        "skin try_preset: yes; status 1348 []",
        "skin try_memory_size: yes; status 1280 []",
        "skin try_create: yes; status 1280 []",
        "skin try_create_in: yes; status 3 [memory]",
        "skin try_step: yes; status 1 [skin]",
        "skin try_run: yes; status 1 [skin]",
        "skin try_cell_count: yes; status 1 [skin]",
        "skin try_cell: yes; status 1349 []",
        "skin try_outline(view): yes; status 3 [xy]",
        "skin try_outline(): yes; status 1349 []",
        "skin try_render: yes; status 1354 []",
        "skin try_render_height(view): yes; status 3 [pixels]",
        "skin try_render_normal(view): yes; status 3 [pixels]",
        "skin try_render_cells(view): yes; status 3 [pixels]",
        "skin try_render_height(): yes; status 1 [skin]",
        "skin try_render_normal(): yes; status 1 [skin]",
        "skin try_render_cells(): yes; status 1346 []",
        "skin try_render_layers: yes; status 775 [layers.time]",
        "skin try_shade(views): yes; status 3 [rgb]",
        "skin try_shade(): yes; status 3 [normal]",
    ];
    expected.extend(lines.map(String::from));
    expected.push(if standard == "c++20" { "std::span views: yes" } else { "std::span views: not C++20" }.into());
    expected.push(if results {
        "calls without try_: return what the twin returns: yes".into()
    } else {
        "calls without try_: throw what the twin returns: yes".into()
    });
    assert_eq!(output.lines().collect::<Vec<_>>(), expected, "{flags:?} {standard}:\n{output}");
}

/// `tests/cpp/results.cpp` built by g++ and clang++ with `flags`, as C++17 and C++20.
fn check_results_mode(flags: &[&str]) {
    for compiler in ["g++", "clang++"] {
        for standard in ["c++17", "c++20"] {
            let (stdout, stderr) =
                build_and_run_flagged(compiler, standard, "tests/cpp/results.cpp", Linkage::Static, flags, &[]);
            assert!(stderr.is_empty(), "{compiler} {standard} {flags:?}: stderr:\n{stderr}");
            check_results(&stdout, flags, standard);
        }
    }
}

/// Without exceptions (and without RTTI), every wrapper call returns its `hibi::Result`.
#[test]
fn cpp_results_without_exceptions_with_gxx_and_clangxx() {
    check_results_mode(NO_EXCEPTIONS);
}

/// With exceptions on, `HIBI_NO_EXCEPTIONS` turns the wrapper into its result mode all the same.
#[test]
fn cpp_results_with_hibi_no_exceptions_with_gxx_and_clangxx() {
    check_results_mode(HIBI_NO_EXCEPTIONS);
}

/// With exceptions, the `try_` twins return results beside the throwing calls.
#[test]
fn cpp_results_beside_exceptions_with_gxx_and_clangxx() {
    check_results_mode(WITH_EXCEPTIONS);
}

#[test]
fn cpp_results_are_clean_under_sanitizers_with_gxx_and_clangxx() {
    for (compiler, flags) in [("g++", NO_EXCEPTIONS), ("clang++", NO_EXCEPTIONS), ("clang++", WITH_EXCEPTIONS)] {
        let (stdout, stderr) =
            build_and_run_flagged(compiler, "c++17", "tests/cpp/results.cpp", Linkage::Sanitized, flags, &[]);
        // Without exceptions the program asks for a 2^62-byte hibi::Buffer, which must come out
        // empty: AddressSanitizer returns NULL (allocator_may_return_null) and says so.
        let refused = "WARNING: AddressSanitizer failed to allocate 0x4000000000000000 bytes";
        let stderr: Vec<&str> = stderr.lines().filter(|l| !l.ends_with(refused)).collect();
        assert!(stderr.is_empty(), "{compiler} {flags:?}: stderr:\n{}", stderr.join("\n"));
        check_results(&stdout, flags, "c++17");
    }
}

#[test]
fn cpp_results_are_clean_under_valgrind() {
    let (stdout, stderr) =
        build_and_run_flagged("g++", "c++17", "tests/cpp/results.cpp", Linkage::Valgrind, NO_EXCEPTIONS, &[]);
    assert!(stderr.is_empty(), "stderr under Valgrind:\n{stderr}");
    check_results(&stdout, NO_EXCEPTIONS, "c++17");
}

/// The glass plate `c_examples/engine.cpp` breaks, drawn by Rust: which of its 160 × 160
/// break-time pixels a crack reached.
fn expected_engine_glass() -> Vec<bool> {
    use hibi_core::glass::{Glass, GlassLayers, GlassParams, GlassRender};

    let params = GlassParams { width: 160.0, height: 160.0, impact: [70.0, 90.0], seed: 11, ..GlassParams::default() };
    let m = params.memory().unwrap();
    let mut memory = m.allocate();
    let mut glass = Glass::new(&params, memory.buffers()).unwrap();
    while !glass.step(u64::MAX).finished {}
    let mut time = vec![0.0f32; 160 * 160];
    let render = GlassRender { width: 160, height: 160, ..GlassRender::default() };
    glass.render(&render, GlassLayers { time: Some(&mut time), ..Default::default() }).unwrap();
    time.iter().map(|t| t.is_finite()).collect()
}

/// A number after `prefix` in `line`, up to the next space.
fn number_after(line: &str, prefix: &str) -> u64 {
    let rest = &line[line.find(prefix).unwrap_or_else(|| panic!("no {prefix:?} in {line:?}")) + prefix.len()..];
    rest.split([' ', ',', ')']).next().unwrap().parse().unwrap_or_else(|_| panic!("not a number: {line:?}"))
}

/// The game loop spreads each model over several frames within its budget (mud's step stops
/// once its work reaches the budget, so a frame overruns it by less than one indivisible piece;
/// skin's, which checks its budget before each cell, by at most one cell's outline and one
/// unit: 2 049), writes four frames of each break-time raster, the last glass frame cracked
/// where Rust's plate is, and the budgeted objects equal unbudgeted runs.
fn check_engine(linkage: Linkage) {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("engine_{linkage:?}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let output =
        build_and_run_with(&cpp_compiler(), "c++17", "c_examples/engine.cpp", linkage, &[dir.to_str().unwrap()]);
    let frames = line(&output, "frames: ");
    let per_model: Vec<u64> = ["glass done after ", "mud after ", "explicit mud after ", "skin after "]
        .map(|p| number_after(frames, p))
        .into();
    assert!(per_model.iter().all(|&f| f > 1), "a model finished in one frame: {frames}");
    assert_eq!(number_after(frames, "frames: "), *per_model.iter().max().unwrap(), "{frames}");
    // Mud overruns by less than one piece: a node's springs (quasi-static, hexagonal: 6), a
    // row's springs in one direction and their rescan (explicit: 2 · 16 columns), or a piece
    // of the network's tracing (at most 64), in every frame, the tracing's included.
    for (name, piece) in [("mud", 6), ("explicit mud", 2 * 16)] {
        let mud = line(&output, &format!("{name}: largest frame work "));
        let (largest, budget) = (number_after(mud, "work "), number_after(mud, "budget "));
        let piece = u64::max(piece, hibi_core::mud::TRACE_PIECE);
        assert!(largest >= budget && largest < budget + piece, "{mud}");
    }
    let skin = line(&output, "skin: largest frame work ");
    let (largest, budget) = (number_after(skin, "work "), number_after(skin, "budget "));
    assert!(largest >= budget && largest < budget + hibi_core::skin::MAX_OUTLINE as u64 + 1, "{skin}");
    // Glass overruns its budget by less than one piece: a cell or entry of a query, a crack
    // looked at, or a step of the face walks in lockstep (2).
    let glass = line(&output, "glass: largest frame work ");
    let (largest, budget) = (number_after(glass, "work "), number_after(glass, "budget "));
    assert!(largest >= budget && largest < budget + hibi_core::glass::STEP_PIECE, "{glass}");
    assert_eq!(line(&output, "wrote "), "wrote 4 frames of each break-time raster");
    // Mud live: every frame renders the network the run shows; from the frame of the first
    // break (or the next: the first trace finishes within the frame's budget unless the break
    // comes at its end) every frame has cracks, and the springs shown rise and never fall, to
    // every spring broken.
    for (name, networks) in [("mud", 4), ("explicit mud", 20)] {
        let live = line(&output, &format!("{name} live: "));
        let (first_break, first_shown) = (number_after(live, "frame "), number_after(live, "from frame "));
        assert!(first_shown <= first_break + 1, "{live}");
        assert_eq!(number_after(live, "on, "), 0, "blank frames after the first crack: {live}");
        assert!(number_after(live, "blank; ") >= networks, "{live}");
        assert_eq!(number_after(live, "falling "), 0, "{live}");
    }
    assert_eq!(
        line(&output, "budgeted = one go:"),
        "budgeted = one go: glass yes, mud yes, explicit mud yes, skin yes"
    );
    // Renders streamed a 32 x 32 tile per call: 25 tiles of each 160 x 160 image and 9 of the
    // 96 x 96 skin, none larger than its tile, every layer equal to the whole image's.
    assert_eq!(
        line(&output, "tiles: "),
        "tiles: 59 render calls, the largest 1024 pixels; streamed = whole: glass yes, mud yes, skin yes"
    );
    // The mud's network and cells built a frame's budget per call: over the budget by less than
    // one piece (the cracks leaving one mesh cell, walked twice; or nine times one ring), equal
    // to the one-call outputs.
    let outputs = line(&output, "mud outputs: ");
    let budget = number_after(outputs, "budget ");
    let (longest, ring) = (number_after(outputs, "longest crack "), number_after(outputs, "largest ring "));
    assert!(number_after(outputs, "network work ") < budget + 1 + 2 * 3 * (longest + 2), "{outputs}");
    assert!(number_after(outputs, "cell work ") < budget + 1 + 9 * ring, "{outputs}");
    assert!(
        number_after(outputs, "; ") > 10 && outputs.ends_with("built = whole: network yes, cells yes"),
        "{outputs}"
    );
    let header = b"P5\n160 160\n255\n";
    for model in ["glass", "mud"] {
        for frame in 0..4 {
            let bytes = std::fs::read(dir.join(format!("{model}_time_{frame:02}.pgm"))).expect("a frame PGM");
            assert_eq!(&bytes[..header.len()], header);
            assert_eq!(bytes.len(), header.len() + 160 * 160);
        }
    }
    let last = std::fs::read(dir.join("glass_time_03.pgm")).unwrap();
    let cracked: Vec<bool> = last[header.len()..].iter().map(|&v| v != 255).collect();
    assert!(cracked == expected_engine_glass(), "the last glass frame is cracked elsewhere than Rust's plate");
}

#[test]
fn engine_example_links_static_library() {
    check_engine(Linkage::Static);
}

#[test]
fn engine_example_is_clean_under_sanitizers() {
    check_engine(Linkage::Sanitized);
}

#[test]
fn engine_example_is_clean_under_valgrind() {
    check_engine(Linkage::Valgrind);
}

/// A property test's finding: the one closed crack of a periodic plate is an island in a cell
/// that wraps around the torus; its outside is a hole in that cell, not an outer ring of
/// negative area, and the statistics count both cells.
#[test]
fn c_mud_island_on_a_torus_is_a_hole_in_a_wrapping_cell() {
    let output = regression("tests/c/mud_island.c");
    assert_eq!(
        output.trim(),
        "rings 2, wrapping 0\n\
         ring 0: hole in a wrapping cell, area negative\n\
         ring 1: outer, area positive\n\
         cells 2, mean area positive"
    );
}

/// Outputs are defined to the byte: `hibi_rng_rand` refuses a range past `FLT_MAX` rather
/// than drawing infinity; destroying NULL leaves `hibi_error_argument()` empty; the progress
/// records and the fragment and cell rings have no padding (their `reserved` words are 0).
#[test]
fn c_outputs_are_defined_to_the_byte() {
    let output = regression("tests/c/outputs_defined.c");
    let expected = [
        "rand FLT_MAX, z 0.9: status 257, out untouched: yes",
        "rand -FLT_MAX, z 0.5: status 257, out untouched: yes",
        "rand FLT_MAX / 2, z 0.9: status 0, finite: yes",
        "rand FLT_MAX, z 0: status 0, finite: yes",
        "after a NULL out: [out]",
        "after hibi_mud_destroy(NULL): []",
        "after the other destroys of NULL: []",
        "mud progress: status 0, size 32, reserved 0: yes",
        "mud cells: status 0, rings yes, reserved 0 in every ring: yes",
        "glass fragments: status 0, rings yes, reserved 0 in every ring: yes",
        "skin progress: status 0, size 32, reserved 0: yes",
    ];
    assert_eq!(output.lines().collect::<Vec<_>>(), expected, "{output}");
}

/// From `*_create_in` to `*_destroy`, nothing allocates: Valgrind's heap summary of a program
/// that drives every model in its own static memory counts 0 allocations.
#[test]
fn c_caller_memory_path_allocates_nothing() {
    let source = "tests/c/caller_memory.c";
    assert_eq!(
        regression("tests/c/caller_memory.c"),
        "rng: status 0\nmud: status 0, cracks yes\nglass: status 0, fragments yes\nskin: status 0\n"
    );
    let (stdout, stderr) = build_and_run_capturing(&c_compiler(), "c99", source, Linkage::HeapCount, &[]);
    assert!(stdout.starts_with("rng: status 0"), "{stdout}");
    let summary = stderr
        .lines()
        .find(|l| l.contains("total heap usage:"))
        .unwrap_or_else(|| panic!("no heap summary:\n{stderr}"));
    assert!(summary.contains("total heap usage: 0 allocs, 0 frees"), "{summary}");
}

/// An irregular lattice's explicit run whose mesh fails the stability test is created (in
/// caller memory of any bytes) and refused by the `hibi_mud_step` that tests the failing node,
/// with the status naming `short_step`, no progress written, and every later step refused too.
#[test]
fn c_an_unstable_irregular_mesh_is_refused_by_step() {
    let output = regression("tests/c/mud_unstable_mesh.c");
    let lines: Vec<&str> = output.lines().collect();
    assert_eq!(lines.len(), 5, "{output}");
    assert_eq!(lines[..2], ["memory_size: status 0", "create_in: status 0"], "{output}");
    let refused = format!("status {} (mud: short_step fails", hibi::HIBI_ERROR_MUD_SHORT_STEP_STABILITY);
    assert!(lines[2].starts_with(&format!("step: {refused}")), "{output}");
    assert!(lines[2].ends_with("after more than 1000 calls: yes, progress untouched: yes []"), "{output}");
    let again = format!("step again: status {}, progress untouched: yes", hibi::HIBI_ERROR_MUD_SHORT_STEP_STABILITY);
    assert_eq!(lines[3], again, "{output}");
    assert_eq!(lines[4], "uncracked: segments 0, vertices 0, edges 0, points 0", "{output}");
}

/// Caller memory may hold anything: every model made with `*_create_in` over memory filled
/// with 0xa5 or 0xff bytes, or fresh from `malloc` and never written, grows the result of
/// `*_create`, byte for byte. (Under Valgrind, `c_tests_are_clean_under_valgrind`, any read of
/// a byte hibi did not write would be an error.)
#[test]
fn c_create_in_any_bytes_grows_the_same_result() {
    let output = regression("tests/c/create_in_any_bytes.c");
    let lines: Vec<&str> = output.lines().collect();
    assert_eq!(lines.len(), 9, "{output}");
    for l in lines {
        assert!(l.ends_with("same as library memory: yes"), "{l}");
    }
}

/// Polygons and rasters share their axes (x right along a row, y down the rows, row 0 at
/// y = 0): laid over each model's crack mask, drawn at the domain's aspect
/// (`hibi_mud_render_params_fit`, `hibi_mud_extent`), the edges of the glass fragments and of
/// the mud cells lie on crack pixels (all but 1 %), and with y flipped most do not; every
/// outer ring's signed area is positive in those axes.
#[test]
fn c_polygons_lie_on_their_crack_masks() {
    let output = regression("tests/c/overlay.c");
    for model in ["glass", "mud"] {
        let l = line(&output, &format!("{model}: "));
        let number = |after: &str| -> f64 {
            let rest = l.split_once(after).unwrap_or_else(|| panic!("{l}")).1;
            rest.split([';', ' ']).next().unwrap().trim_end_matches(',').parse().unwrap()
        };
        assert!(number("on cracks ") >= 0.99, "{l}");
        assert!(number("flipped ") <= 0.5, "{l}");
        let (positive, outer) = l.split_once("outer rings positive ").unwrap().1.split_once(" of ").unwrap();
        assert_eq!(positive, outer, "{l}");
        assert!(outer.parse::<u32>().unwrap() > 10, "{l}");
    }
    assert!(line(&output, "mud extent ").ends_with("(aspect kept: yes)"), "{output}");
}

/// C lists every model's presets, the core's names in the core's order, each accepted by
/// `hibi_*_params_preset`.
#[test]
fn c_lists_the_presets() {
    let output = regression("tests/c/presets.c");
    let expected = format!(
        "mud: {}\nglass: {}\nskin: {}\npast the end: NULL\n",
        hibi_core::mud::PRESETS.join(" "),
        hibi_core::glass::PRESETS.join(" "),
        hibi_core::skin::PRESETS.join(" ")
    );
    assert_eq!(output, expected);
}

/// Model B at the ends of its ranges (`tests/c/glass_extremes.c`): plates wider than 65536 px
/// (1e15, 1e20) are refused by name, nothing created, and the fragments of a 65536 px plate
/// cover it; radial cracks of 1e8 to 1e30 px a step leave fragments whose signed areas add up
/// to the plate's, relative error at most 1e-4, for seeds 1 to 10; large cracks of 1e-30 to
/// 1e-5 px a step finish at the time limit of 32 768 steps within 1e9 units, their fragments
/// covering the plate.
#[test]
fn c_glass_extremes_finish_and_their_fragments_cover_the_plate() {
    let output = regression("tests/c/glass_extremes.c");
    let mut expected = Vec::new();
    for width in ["1e+15", "1e+20"] {
        expected.push(format!(
            "width {width}: status 1024 and 1024, glass: width and height must be finite and within [1, 65536], \
             nothing created: yes"
        ));
    }
    expected.push("width 65536: status 0, finished 1, areas sum to the plate: yes".to_owned());
    for speed in ["1e+08", "1e+10", "1e+20", "1e+30"] {
        for seed in 1..=10 {
            expected
                .push(format!("radial_speed {speed} seed {seed}: status 0, finished 1, areas sum to the plate: yes"));
        }
    }
    for speed in ["1e-30", "1e-20", "1e-06", "1e-05"] {
        expected.push(format!(
            "large_speed {speed}: status 0, finished 1, time 32768, work within 1e9: yes, areas sum to the plate: yes"
        ));
    }
    assert_eq!(output.lines().collect::<Vec<_>>(), expected, "{output}");
}

/// Every model's heaviest calls run on a thread of 24 KiB, the size the header promises is
/// enough (the program's sanitizer build gets a larger thread for the instrumentation's own
/// frames; its plain static build below runs on the 24 KiB).
#[test]
fn c_every_model_runs_on_a_24_kib_thread() {
    let expected = "every model on a 24 KiB thread: status 0\n";
    assert_eq!(regression("tests/c/thread_stack.c"), expected);
    assert_eq!(build_and_run(&c_compiler(), "c99", "tests/c/thread_stack.c", Linkage::Static), expected);
}

/// Explicit runs whose f32 lattice cannot bring every force below the tolerance end
/// (`tests/c/mud_runs_end.c`): open plates grown to the end by the explicit solver, unbreakable
/// or cracking on the way, reach finished within 1e8 units of work at a growth of 100 or more,
/// with 0, 0 and 33 springs broken.
#[test]
fn c_explicit_mud_runs_end_where_f32_cannot_settle() {
    let output = regression("tests/c/mud_runs_end.c");
    let expected = [
        "hexagonal 3x3, unbreakable, gamma 0.5: status 0, finished 1, growth 100 or more: yes, broken 0",
        "square 3x3, unbreakable, gamma 0.5: status 0, finished 1, growth 100 or more: yes, broken 0",
        "hexagonal 4x4, break stretch 3, gamma 0.99: status 0, finished 1, growth 100 or more: yes, broken 33",
    ];
    assert_eq!(output.lines().collect::<Vec<_>>(), expected, "{output}");
}

/// The layers the C program `tests/c/every_layer.c` wrote into `dir` for `model`.
fn c_layer(dir: &Path, model: &str, layer: &str) -> Vec<u8> {
    std::fs::read(dir.join(format!("{model}.{layer}"))).unwrap_or_else(|e| panic!("{model}.{layer}: {e}"))
}

/// Every [`hibi_tests::EveryLayer`] layer as the bytes C holds it in, by its C name.
fn rust_layers(every: &hibi_tests::EveryLayer, crack: bool) -> Vec<(&'static str, Vec<u8>)> {
    let floats = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let mut out = vec![
        ("mask", every.mask.clone()),
        ("height", floats(&every.height)),
        ("height16", every.height16.iter().flat_map(|x| x.to_le_bytes()).collect()),
        ("normal", floats(&every.normal.concat())),
        ("normal_rgb8", every.normal_rgb8.concat()),
        ("preview", every.preview.concat()),
    ];
    if crack {
        out.push(("time", floats(&every.time)));
    } else {
        out.push(("cell", every.cell.iter().flat_map(|x| x.to_le_bytes()).collect()));
    }
    out
}

/// A PNG the command line wrote: width, height and its samples (16-bit ones big-endian, as
/// PNG stores them).
fn read_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut reader = png::Decoder::new(std::io::BufReader::new(file)).read_info().expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size().expect("a size")];
    let info = reader.next_frame(&mut buf).expect("a frame");
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Runs the command line for `model` with `args` and each layer, and checks each PNG's pixels
/// against the layers C drew (the time layer as the command line encodes it: 0 at the earliest
/// break, 65534 at the latest, 65535 where nothing broke).
fn cli_pictures_equal_c_layers(dir: &Path, model: &str, args: &[&str], layers: &[&str]) {
    let hibi = hibi_tests::cli_dir().join("hibi");
    for &layer in layers {
        let png = dir.join(format!("cli-{model}-{layer}.png"));
        let status = std::process::Command::new(&hibi)
            .arg(model)
            .args(args)
            .args(["--quiet", "--layer", layer, "--output"])
            .arg(&png)
            .status()
            .expect("run hibi");
        assert!(status.success(), "hibi {model} {args:?} --layer {layer}");
        let (_, _, pixels) = read_png(&png);
        let expected: Vec<u8> = match layer {
            "mask" => c_layer(dir, model, "mask"),
            "height" => c_layer(dir, model, "height16").chunks(2).flat_map(|b| [b[1], b[0]]).collect(),
            "normal" => c_layer(dir, model, "normal_rgb8"),
            "shaded" => c_layer(dir, model, "preview").chunks(4).flat_map(|p| [p[0], p[1], p[2]]).collect(),
            "time" => {
                let t: Vec<f32> =
                    c_layer(dir, model, "time").chunks(4).map(|b| f32::from_le_bytes(b.try_into().unwrap())).collect();
                let finite = t.iter().copied().filter(|t| t.is_finite());
                let (first, last) = finite.fold((f32::MAX, f32::MIN), |(a, b), t| (a.min(t), b.max(t)));
                let span = if last > first { last - first } else { 1.0 };
                let code = |t: f32| if t.is_finite() { ((t - first) / span * 65534.0).round() as u16 } else { 65535 };
                t.iter().flat_map(|&t| code(t).to_be_bytes()).collect()
            }
            other => unreachable!("{other}"),
        };
        assert!(pixels == expected, "hibi {model} --layer {layer}: the PNG's pixels differ from C's layer");
    }
}

/// One call draws every layer of every model from C; each layer's bytes equal Rust's render of
/// the same scene, and the command line's PNG of each layer has the same pixels; a tile of each
/// model equals the whole image there; layers a model lacks and tiles past the edge are refused
/// by name.
#[test]
fn c_renders_every_layer_of_every_model_in_one_call() {
    use hibi_core::glass::{Glass, GlassParams, GlassRender};
    use hibi_core::mud::{Mud, MudParams, MudRender};
    use hibi_core::skin::{Skin, SkinParams, SkinRender};
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("every_layer");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a directory for the layers");
    let output = regression("tests/c/every_layer.c");
    // Again, writing the layers.
    let (written, stderr) = build_and_run_capturing(
        &c_compiler(),
        "c99",
        "tests/c/every_layer.c",
        Linkage::Sanitized,
        &[dir.to_str().expect("a UTF-8 path")],
    );
    assert!(stderr.is_empty() && written == output, "{stderr}");
    for model in ["mud", "glass", "skin"] {
        assert_eq!(line(&output, &format!("{model} tile equal")), format!("{model} tile equal: yes"));
    }
    assert_eq!(line(&output, "mud cell layer"), "mud cell layer: status 775, layers.cell");
    assert_eq!(line(&output, "glass tile past"), "glass tile past the edge: status 776, tile");
    assert_eq!(line(&output, "skin mask without"), "skin mask without scratch: status 3, layers.scratch");

    // Rust, the same scenes.
    let params = MudParams { columns: 32, rows: 32, ..MudParams::default() };
    let mut store = params.memory().unwrap().allocate::<f32>();
    let mut mud = Mud::new(&params, store.buffers()).unwrap();
    mud.run().unwrap();
    let render = MudRender::fit(mud.extent(), 128);
    let mut every = hibi_tests::EveryLayer::new(render.width, render.height);
    mud.render(&render, every.layers(true)).unwrap();
    assert!(line(&output, "mud ").starts_with(&format!("mud {}x{}:", render.width, render.height)));
    for (name, bytes) in rust_layers(&every, true) {
        assert!(c_layer(&dir, "mud", name) == bytes, "mud {name}: C's bytes differ from Rust's");
    }
    let size = format!("{}x{}", render.width, render.height);
    let mud_args = ["--columns", "32", "--rows", "32", "--size", &size];
    cli_pictures_equal_c_layers(&dir, "mud", &mud_args, &["mask", "height", "normal", "time", "shaded"]);

    let params = GlassParams { width: 160.0, height: 120.0, impact: [70.0, 50.0], ..GlassParams::default() };
    let mut store = params.memory().unwrap().allocate();
    let mut glass = Glass::new(&params, store.buffers()).unwrap();
    glass.run();
    let render = GlassRender { width: 160, height: 120, ..GlassRender::default() };
    let mut every = hibi_tests::EveryLayer::new(160, 120);
    glass.render(&render, every.layers(true)).unwrap();
    for (name, bytes) in rust_layers(&every, true) {
        assert!(c_layer(&dir, "glass", name) == bytes, "glass {name}: C's bytes differ from Rust's");
    }
    let glass_args = ["--width", "160", "--height", "120", "--impact", "70,50", "--size", "160x120"];
    cli_pictures_equal_c_layers(&dir, "glass", &glass_args, &["mask", "height", "normal", "time", "shaded"]);

    let params = SkinParams { width: 120, height: 100, ..hibi_core::skin::preset("fig19a").unwrap() };
    let mut store = params.memory().unwrap().allocate();
    let mut skin = Skin::<f32>::new(&params, store.buffers()).unwrap();
    skin.run();
    let mut every = hibi_tests::EveryLayer::new(120, 100);
    skin.render(&SkinRender { cell_level: 1, ..SkinRender::default() }, every.layers(false)).unwrap();
    for (name, bytes) in rust_layers(&every, false) {
        assert!(c_layer(&dir, "skin", name) == bytes, "skin {name}: C's bytes differ from Rust's");
    }
    let skin_args = ["--preset", "fig19a", "--size", "120x100"];
    cli_pictures_equal_c_layers(&dir, "skin", &skin_args, &["mask", "height", "normal", "shaded"]);
}
