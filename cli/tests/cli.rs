//! The `hibi` binary as a shell user meets it: every model renders a small PNG of the size
//! asked for, every layer in its documented format, animations hold their frames, bad options
//! fail with status 2 and a message naming the option, and failures leave no file behind.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs `hibi` with `args`.
fn hibi(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hibi")).args(args).output().expect("the binary runs")
}

/// A fresh, empty directory for one test, removed with everything in it when the test ends
/// (passed or failed).
struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

/// A [`Scratch`] directory named after the test.
fn scratch(name: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("hibi-cli-test-{}-{name}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    Scratch(dir)
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Asserts success and returns stderr.
fn succeeds(args: &[&str]) -> String {
    let out = hibi(args);
    assert!(out.status.success(), "hibi {args:?} failed: {}", text(&out.stderr));
    text(&out.stderr)
}

/// Asserts failure with `status` and returns stderr.
fn fails(args: &[&str], status: i32) -> String {
    let out = hibi(args);
    assert_eq!(out.status.code(), Some(status), "hibi {args:?}: {}", text(&out.stderr));
    text(&out.stderr)
}

/// Decodes a PNG: width, height, colour type, bit depth, frames.
fn decode(path: &Path) -> (u32, u32, png::ColorType, png::BitDepth, u32) {
    let file = fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut reader = png::Decoder::new(std::io::BufReader::new(file)).read_info().expect("a PNG");
    let frames = reader.info().animation_control.map_or(1, |a| a.num_frames);
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).expect("pixel data");
    (info.width, info.height, info.color_type, info.bit_depth, frames)
}

/// The files in `dir`.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> =
        fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    names
}

/// A small, fast mud lattice.
const SMALL_MUD: [&str; 4] = ["--columns", "24", "--rows", "28"];

#[test]
fn every_model_writes_a_png_of_the_size_asked_for() {
    let dir = scratch("models");
    let out = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let mud = out("mud.png");
    succeeds(&[&["mud", "--size", "40x32", "-o", &mud], &SMALL_MUD[..]].concat());
    assert_eq!(decode(Path::new(&mud)), (40, 32, png::ColorType::Rgb, png::BitDepth::Eight, 1));
    let glass = out("glass.png");
    let said = succeeds(&["glass", "--preset", "fig15a", "--size", "48x36", "-o", &glass]);
    assert!(said.contains("M = 114"), "{said}");
    assert_eq!(decode(Path::new(&glass)), (48, 36, png::ColorType::Rgb, png::BitDepth::Eight, 1));
    let skin = out("skin.png");
    succeeds(&["skin", "--preset", "fig19a", "--size", "56x40", "-o", &skin]);
    assert_eq!(decode(Path::new(&skin)), (56, 40, png::ColorType::Rgb, png::BitDepth::Eight, 1));
    // Nothing but the pictures: no temporary file is left.
    assert_eq!(listing(&dir), ["glass.png", "mud.png", "skin.png"]);
}

#[test]
fn every_layer_has_its_documented_format() {
    let dir = scratch("layers");
    use png::BitDepth::{Eight, Sixteen};
    use png::ColorType::{Grayscale, Rgb};
    let layers = [
        ("mask", Grayscale, Eight),
        ("height", Grayscale, Sixteen),
        ("normal", Rgb, Eight),
        ("time", Grayscale, Sixteen),
        ("shaded", Rgb, Eight),
    ];
    for (layer, colour, depth) in layers {
        let path = dir.join(format!("mud-{layer}.png")).to_string_lossy().into_owned();
        succeeds(&[&["mud", "-q", "--size", "32", "--layer", layer, "-o", &path], &SMALL_MUD[..]].concat());
        assert_eq!(decode(Path::new(&path)), (32, 32, colour, depth, 1), "mud {layer}");
        let path = dir.join(format!("glass-{layer}.png")).to_string_lossy().into_owned();
        succeeds(&["glass", "-q", "--size", "32", "--layer", layer, "-o", &path]);
        assert_eq!(decode(Path::new(&path)), (32, 32, colour, depth, 1), "glass {layer}");
        if layer != "time" {
            let path = dir.join(format!("skin-{layer}.png")).to_string_lossy().into_owned();
            succeeds(&["skin", "-q", "--size", "32", "--layer", layer, "-o", &path]);
            assert_eq!(decode(Path::new(&path)), (32, 32, colour, depth, 1), "skin {layer}");
        }
    }
}

#[test]
fn pictures_are_the_same_bytes_on_any_number_of_threads() {
    let dir = scratch("threads");
    let models: [&[&str]; 3] = [&["mud", "--columns", "24", "--rows", "28"], &["glass"], &["skin"]];
    for model in models {
        for layer in ["mask", "height", "normal", "time", "shaded"] {
            if model[0] == "skin" && layer == "time" {
                continue;
            }
            let files: Vec<Vec<u8>> = ["1", "2", "5"]
                .iter()
                .map(|threads| {
                    let path = dir.join(format!("{}-{layer}-{threads}.png", model[0])).to_string_lossy().into_owned();
                    let args = ["-q", "--size", "61x37", "--layer", layer, "--threads", threads, "-o", &path];
                    succeeds(&[model, &args[..]].concat());
                    fs::read(&path).unwrap()
                })
                .collect();
            assert!(files.iter().all(|f| *f == files[0]), "{} {layer}", model[0]);
        }
    }
    // The frames of a growth too.
    let frames: Vec<Vec<u8>> = ["1", "3"]
        .iter()
        .map(|threads| {
            let path = dir.join(format!("growth-{threads}.png")).to_string_lossy().into_owned();
            succeeds(&["glass", "-q", "--size", "40", "--frames", "4", "--threads", threads, "-o", &path]);
            fs::read(&path).unwrap()
        })
        .collect();
    assert_eq!(frames[0], frames[1]);
}

#[test]
fn growth_is_an_animated_png_or_a_numbered_sequence() {
    let dir = scratch("growth");
    let apng = dir.join("growth.png").to_string_lossy().into_owned();
    succeeds(&[&["mud", "--size", "32", "--frames", "5", "-o", &apng], &SMALL_MUD[..]].concat());
    assert_eq!(decode(Path::new(&apng)).4, 5);
    let glass = dir.join("glass.png").to_string_lossy().into_owned();
    succeeds(&["glass", "--size", "32", "--frames", "3", "--layer", "mask", "--sequence", "-o", &glass]);
    for k in 1..=3 {
        let frame = dir.join(format!("glass-00{k}.png"));
        assert_eq!(decode(&frame), (32, 32, png::ColorType::Grayscale, png::BitDepth::Eight, 1));
    }
    assert_eq!(listing(&dir), ["glass-001.png", "glass-002.png", "glass-003.png", "growth.png"]);
}

#[test]
fn bad_options_are_usage_errors_naming_the_option() {
    let cases: [(&[&str], &str); 16] = [
        (&["mud", "--size", "0x10"], "--size"),
        (&["mud", "--rows", "5"], "--rows"),
        (&["mud", "--young-modulus", "-1"], "--young-modulus"),
        // Known only once the irregular lattice is built: still a usage error, no panic.
        (
            &[
                "mud",
                "--topology",
                "irregular",
                "--solver",
                "explicit",
                "--short-step",
                "0.0102",
                "--columns",
                "16",
                "--rows",
                "16",
            ],
            "--short-step",
        ),
        (&["mud", "--bogus"], "--bogus"),
        (&["mud", "--preset", "fig99"], "--preset"),
        (&["mud", "--layer", "time", "--frames", "3"], "--layer"),
        (&["glass", "--impact", "700,10"], "--impact"),
        (&["glass", "--turn-limit", "200"], "--turn-limit"),
        (&["skin", "--layer", "time"], "--layer"),
        (&["skin", "--spacing", "3=5"], "--spacing"),
        (&["skin", "--profile", "0,3 10,0"], "--profile"),
        (&["skin", "--frames", "3"], "--frames"),
        (&["skin", "--ambient", "1.5"], "--ambient"),
        (&["skin", "--furrow", "0.5,2,0.5"], "--furrow"),
        (&["glass", "--threads", "0"], "--threads"),
    ];
    let dir = scratch("usage");
    for (args, option) in cases {
        let target = dir.join("never.png").to_string_lossy().into_owned();
        let args = [args, &["-o", &target]].concat();
        let message = fails(&args, 2);
        assert!(message.contains(option), "hibi {args:?} should name {option}: {message}");
        assert!(message.starts_with("error:"), "hibi {args:?}: {message}");
    }
    assert!(listing(&dir).is_empty(), "{:?}", listing(&dir));
    // No subcommand at all is a usage error too.
    assert!(fails(&[], 2).contains("Usage:"));
}

#[test]
fn an_unwritable_output_fails_clearly_before_any_work() {
    let dir = scratch("unwritable");
    let missing = dir.join("no-such-directory").join("out.png").to_string_lossy().into_owned();
    let message = fails(&["skin", "--size", "16", "-o", &missing], 1);
    assert!(message.starts_with("hibi: cannot write"), "{message}");
    assert!(message.contains("does not exist"), "{message}");
    let message = fails(&["glass", "--size", "16", "-o", &dir.to_string_lossy()], 1);
    assert!(message.contains("is a directory"), "{message}");
    let file = dir.join("file");
    fs::write(&file, b"not a directory").unwrap();
    let message = fails(&["gallery", &file.to_string_lossy()], 1);
    assert!(message.contains("not a directory"), "{message}");
    assert_eq!(listing(&dir), ["file"]);
}

#[test]
fn a_failed_run_leaves_the_previous_file_untouched_and_no_temporary_file() {
    let dir = scratch("atomic");
    let target = dir.join("glass.png");
    fs::write(&target, b"the previous picture").unwrap();
    // The plate runs out of room for cracks mid-run.
    let message = fails(&["glass", "--max-vertices", "64", "--size", "16", "-o", &target.to_string_lossy()], 1);
    assert!(message.contains("--max-vertices"), "{message}");
    assert_eq!(fs::read(&target).unwrap(), b"the previous picture");
    assert_eq!(listing(&dir), ["glass.png"]);
}

#[test]
fn help_documents_every_parameter() {
    let help = text(&hibi(&["mud", "--help"]).stdout);
    for option in ["--young-modulus", "--shear-modulus", "--anisotropy-ratio", "--target-shrink", "--layer", "--frames"]
    {
        assert!(help.contains(option), "mud --help lacks {option}");
    }
    let help = text(&hibi(&["glass", "--help"]).stdout);
    for option in ["--radial-mean", "--large-speed", "--sector-angle", "--impact", "--line-width"] {
        assert!(help.contains(option), "glass --help lacks {option}");
    }
    let help = text(&hibi(&["skin", "--help"]).stdout);
    for option in ["--jitter-ratio", "--perturbation", "--stretch", "--profile", "--roundness", "--light"] {
        assert!(help.contains(option), "skin --help lacks {option}");
    }
    assert!(text(&hibi(&["--help"]).stdout).contains("gallery"));
}

#[test]
fn the_gallery_renders_every_figure_and_an_index_of_them() {
    let dir = scratch("gallery");
    let said = succeeds(&["gallery", &dir.to_string_lossy(), "--size", "128", "--frames", "3"]);
    assert!(said.contains("index.html"), "{said}");
    let index = fs::read_to_string(dir.join("index.html")).unwrap();
    // Every picture the page shows exists and decodes; every figure preset is on it.
    let mut pictures = 0;
    for piece in index.split("src=\"").skip(1) {
        let name = &piece[..piece.find('"').unwrap()];
        let (width, ..) = decode(&dir.join(name));
        assert!(width >= 128 / 2, "{name}: {width}");
        pictures += 1;
    }
    let presets = hibi_core::mud::PRESETS.len() + hibi_core::glass::PRESETS.len() + hibi_core::skin::PRESETS.len();
    assert!(pictures > presets, "{pictures} pictures for {presets} presets");
    for (model, names) in [
        ("mud", &hibi_core::mud::PRESETS[..]),
        ("glass", &hibi_core::glass::PRESETS),
        ("skin", &hibi_core::skin::PRESETS),
    ] {
        for name in names {
            assert!(index.contains(&format!("hibi {model} --preset {name} ")), "{model} {name}");
            assert_eq!(decode(&dir.join(format!("{model}-{name}.png"))).0, 128, "{model} {name}");
        }
    }
    assert_eq!(decode(&dir.join("mud-fig10.png")).4, 3, "the growth animation");
    assert_eq!(decode(&dir.join("mud-tile-2x2.png")).0, 128, "the tiled texture");
    assert!(!listing(&dir).iter().any(|f| f.ends_with(".tmp")));
    // On one thread, every file is the same (the page names its own directory).
    let alone = scratch("gallery-one-thread");
    succeeds(&["gallery", &alone.to_string_lossy(), "-q", "--size", "128", "--frames", "3", "--threads", "1"]);
    assert_eq!(listing(&alone), listing(&dir));
    for name in listing(&dir) {
        let (a, b) = (fs::read(dir.join(&name)).unwrap(), fs::read(alone.join(&name)).unwrap());
        if name == "index.html" {
            let a = text(&a).replace(&*dir.to_string_lossy(), "DIR");
            assert_eq!(a, text(&b).replace(&*alone.to_string_lossy(), "DIR"));
        } else {
            assert!(a == b, "{name} differs on one thread");
        }
    }
}
