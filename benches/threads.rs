//! What the command-line tool gains from a second thread, on whole commands as a user runs
//! them: a 2048² picture of each model (the model grows on one thread, its picture is drawn in
//! bands, one per thread, and the PNG is encoded on one) and the default gallery (one figure per
//! thread). Each command runs with `--threads 1` and `--threads 2`, alternately, three times;
//! the table gives the fastest of each and their ratio, and checks that both wrote the same
//! bytes. The table goes to `docs/src/generated/bench-threads.md`, which the performance page
//! includes.
//!
//! `cargo bench --bench threads`

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use hibi_tests::{load_average, write_bench_tables};

/// Runs `hibi args… --threads N` and returns how long it took.
fn timed(hibi: &Path, args: &[String], threads: usize) -> Duration {
    let start = Instant::now();
    let status =
        Command::new(hibi).args(args).args(["--quiet", "--threads", &threads.to_string()]).status().expect("run hibi");
    let took = start.elapsed();
    assert!(status.success(), "hibi {args:?} --threads {threads} failed");
    took
}

/// The files under `path` (itself if it is a file), with their bytes, by name.
fn contents(path: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    if path.is_file() {
        return vec![(PathBuf::new(), std::fs::read(path).expect("read the output"))];
    }
    let mut files: Vec<_> = std::fs::read_dir(path)
        .expect("read the gallery")
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "png"))
        .map(|p| (p.file_name().expect("a file").into(), std::fs::read(&p).expect("read a picture")))
        .collect();
    files.sort();
    files
}

fn main() {
    let hibi = hibi_tests::cli_dir().join("hibi");
    let dir = std::env::temp_dir().join(format!("hibi-bench-threads-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch directory");
    let load = load_average();
    println!("hibi on 1 and 2 threads, fastest of 3 runs each");
    let mut tables = String::from("| command | 1 thread | 2 threads | speed-up |\n|---|---|---|---|\n");
    let cases: [(&str, &[&str]); 5] = [
        ("hibi mud --size 2048 (shaded)", &["mud", "--size", "2048"]),
        ("hibi mud --size 2048 --layer height", &["mud", "--size", "2048", "--layer", "height"]),
        ("hibi glass --size 2048 (shaded)", &["glass", "--size", "2048"]),
        ("hibi skin --size 2048 (shaded)", &["skin", "--size", "2048"]),
        ("hibi gallery DIR (400 px, 24 frames)", &["gallery"]),
    ];
    for (name, args) in cases {
        let output = |threads: usize| {
            let out = dir.join(format!("{}-{threads}{}", args[0], if args[0] == "gallery" { "" } else { ".png" }));
            let mut all: Vec<String> = args.iter().map(|a| a.to_string()).collect();
            if args[0] == "gallery" {
                all.push(out.to_string_lossy().into_owned());
            } else {
                all.extend(["-o".to_string(), out.to_string_lossy().into_owned()]);
            }
            (out, all)
        };
        let (mut one, mut two) = (Duration::MAX, Duration::MAX);
        for _ in 0..3 {
            one = one.min(timed(&hibi, &output(1).1, 1));
            two = two.min(timed(&hibi, &output(2).1, 2));
        }
        assert!(contents(&output(1).0) == contents(&output(2).0), "{name}: the pictures differ");
        let ratio = one.as_secs_f64() / two.as_secs_f64();
        let row = format!("| `{name}` | {:.2} s | {:.2} s | {ratio:.2}× |\n", one.as_secs_f64(), two.as_secs_f64());
        print!("{row}");
        tables.push_str(&row);
    }
    write_bench_tables("bench-threads.md", "cargo bench --bench threads", [load, load_average()], &tables);
    std::fs::remove_dir_all(&dir).expect("remove the scratch directory");
}
