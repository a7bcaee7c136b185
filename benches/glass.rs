//! Model B benchmark: the paper's 640×640 plate, M_ave = 100; generation, then the mask and
//! the time map, averaged over 200 seeds. Prints the times and writes their ratios, the
//! performance page's table, to `docs/src/generated/bench-glass.md`.
//!
//!     cargo bench --bench glass

use std::time::{Duration, Instant};

use hibi_core::glass::{Glass, GlassLayers, GlassParams, GlassRender};
use hibi_tests::{load_average, write_bench_tables};

fn main() {
    let load = load_average();
    let base = GlassParams::default();
    let m = base.memory().expect("valid parameters");
    let mut memory = m.allocate();
    let render = GlassRender::default();
    let (mut mask, mut time) = (vec![0u8; 640 * 640], vec![0.0f32; 640 * 640]);
    let (mut generation, mut masks, mut times) = (Duration::ZERO, Duration::ZERO, Duration::ZERO);
    let plates = 200u32;
    for seed in 0..u64::from(plates) {
        let params = GlassParams { seed, ..base };
        let start = Instant::now();
        let mut glass = Glass::new(&params, memory.buffers()).expect("memory suffices");
        while !glass.step(u64::MAX).finished {}
        generation += start.elapsed();
        let start = Instant::now();
        glass.render(&render, GlassLayers { mask: Some(&mut mask), ..Default::default() }).expect("buffer suffices");
        masks += start.elapsed();
        let start = Instant::now();
        glass.render(&render, GlassLayers { time: Some(&mut time), ..Default::default() }).expect("buffer suffices");
        times += start.elapsed();
    }
    let load = [load, load_average()];
    let ms = |d: Duration| d.as_secs_f64() * 1e3 / f64::from(plates);
    println!("| 640×640, M_ave = 100 (mean of {plates} seeds) | time |");
    println!("|---|---|");
    println!("| generation | {:.2} ms |", ms(generation));
    println!("| mask | {:.2} ms |", ms(masks));
    println!("| time map | {:.2} ms |", ms(times));
    let ratio = |d: Duration| d.as_secs_f64() / generation.as_secs_f64();
    let tables = format!(
        "| step, mean of {plates} seeds | ÷ generation |\n|---|---|\n\
         | generation (`Glass::new` and stepping to the end) | 1 |\n\
         | the crack mask, 640 × 640 | {:.2}× |\n\
         | the break-time map, 640 × 640 | {:.2}× |\n",
        ratio(masks),
        ratio(times)
    );
    write_bench_tables("bench-glass.md", "cargo bench --bench glass", load, &tables);
}
