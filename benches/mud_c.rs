//! Model A's outputs timed from C: builds `benches/c/mud_outputs.c` against the release static
//! library the way the C tests link it (`tests/c_examples.rs`: `libhibi.a` from
//! [`c_library_dir`], the system's `cc` with `-O2`), runs it and prints its table: on the default
//! 128² run, each output with the counts call a C caller makes first to size its buffers
//! (network, cells) and a 512-pixel-wide height render, the median of 21 calls each, in
//! milliseconds and as a fraction of the run's own time. Writes the fractions, the performance
//! page's table, to `docs/src/generated/bench-mud-c.md`.
//!
//!     cargo bench --bench mud_c

use hibi_tests::{NATIVE_STATIC_LIBS, c_library_dir, load_average, tool, workspace_root, write_bench_tables};

fn main() {
    let root = workspace_root();
    let exe = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("mud_outputs");
    let compiler = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let compiled = tool(&compiler)
        .args(["-std=c99", "-O2", "-Wall", "-Wextra", "-Wpedantic", "-Werror", "-I"])
        .arg(root.join("include"))
        .arg(root.join("benches/c/mud_outputs.c"))
        .arg("-o")
        .arg(&exe)
        .arg(c_library_dir().join("libhibi.a"))
        .args(NATIVE_STATIC_LIBS)
        .output()
        .expect("run the C compiler");
    assert!(
        compiled.status.success(),
        "{compiler} benches/c/mud_outputs.c failed:\n{}",
        String::from_utf8_lossy(&compiled.stderr)
    );
    let load = load_average();
    let ran = std::process::Command::new(&exe).output().expect("run the C program");
    assert!(ran.status.success(), "benches/c/mud_outputs.c failed:\n{}", String::from_utf8_lossy(&ran.stderr));
    let load = [load, load_average()];
    let printed = String::from_utf8_lossy(&ran.stdout);
    print!("{printed}");
    // The outputs' rows, each call with its fraction of the run (the time column left out).
    let mut tables = String::from(
        "| from C, 128² default run, median of 21 calls | ÷ the run (`hibi_mud_create`, then `hibi_mud_step` to the end) |\n|---|---|\n",
    );
    for line in printed.lines().filter(|l| l.starts_with("| `hibi_mud_")) {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        assert!(cells.len() == 5, "a row of three columns: {line}");
        tables += &format!("| {} | {} |\n", cells[1], cells[3]);
    }
    write_bench_tables("bench-mud-c.md", "cargo bench --bench mud_c", load, &tables);
}
