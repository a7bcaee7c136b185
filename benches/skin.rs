//! Model C benchmark: the Fig. 19a preset (400×400, three levels, perturbation 0.1), height
//! and normal maps, against FastNoiseLite's cellular noise (Distance2Sub, Euclidean, cell size
//! 40 px like our level 1) on the same grid. Every figure is the median of several runs, after
//! one untimed warm-up run.
//!
//!     cargo bench --bench skin
//!
//! FastNoiseLite's normal is taken two ways: by central differences on its value grid
//! (402×402 evaluations, the usual way to get a normal map from noise), and pointwise, with
//! four extra evaluations per pixel (x ± 1, y ± 1). A last row sums three octaves a third apart
//! (FBm, lacunarity 3), as our three levels are, normal again from its grid. Each of hibi's
//! maps is also rendered alone, as a caller that wants one layer renders it (printed only).
//!
//! Prints the times and writes the ratios, the performance page's tables, to
//! `docs/src/generated/bench-skin.md`.

use std::hint::black_box;
use std::time::{Duration, Instant};

use fastnoise_lite::FractalType;
use hibi_core::skin::{Skin, SkinLayers, SkinRender, preset};
use hibi_tests::{load_average, write_bench_tables};

#[path = "support/cellular.rs"]
mod cellular;
use cellular::{SPACING, cellular, normal, on_grid};

/// Timed runs per measurement.
const RUNS: usize = 10;

fn median(mut times: Vec<Duration>) -> Duration {
    times.sort();
    let n = times.len();
    if n % 2 == 1 { times[n / 2] } else { (times[n / 2 - 1] + times[n / 2]) / 2 }
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// How long `f` takes.
fn timed(f: impl FnOnce()) -> Duration {
    let start = Instant::now();
    f();
    start.elapsed()
}

fn main() {
    let load = load_average();
    let params = preset("fig19a").expect("preset exists");
    let (w, h) = (params.width as usize, params.height as usize);
    let pixels = w * h;
    let m = params.memory().expect("valid parameters");
    let mut memory = m.allocate();
    let (mut height, mut normals) = (vec![0.0f32; pixels], vec![[0.0f32; 3]; pixels]);

    let noise = black_box(cellular());
    let mut octaves = cellular();
    octaves.set_fractal_type(Some(FractalType::FBm));
    octaves.set_fractal_octaves(Some(3));
    octaves.set_fractal_lacunarity(Some(3.0));
    let octaves = black_box(octaves);
    let (gw, gh) = (w + 2, h + 2);
    let mut grid = vec![0.0f32; gw * gh];

    // Every measurement once per round, so that a slow spell of the machine hits them alike;
    // round 0 warms up and is not counted.
    let mut times = [(); 9].map(|()| Vec::with_capacity(RUNS));
    let mut cell_count = 0;
    for round in 0..=RUNS {
        // Ours: build, then render, into the same buffers each round.
        let start = Instant::now();
        let mut skin = Skin::<f32>::new(black_box(&params), memory.buffers()).expect("memory suffices");
        skin.run();
        let built = start.elapsed();
        let layers = SkinLayers { height: Some(&mut height), normal: Some(&mut normals), ..SkinLayers::default() };
        skin.render(&SkinRender::default(), layers).expect("buffers suffice");
        let total = start.elapsed();
        cell_count = skin.cells().len();
        black_box((&height, &normals));
        // Each map on its own, as a caller that wants one layer renders it.
        let render = SkinRender::default();
        let height_only = timed(|| {
            let layers = SkinLayers { height: Some(&mut height), ..SkinLayers::default() };
            skin.render(&render, layers).expect("buffers suffice");
            black_box(&height);
        });
        let normal_only = timed(|| {
            let layers = SkinLayers { normal: Some(&mut normals), ..SkinLayers::default() };
            skin.render(&render, layers).expect("buffers suffice");
            black_box(&normals);
        });

        // FastNoiseLite: the value alone, one evaluation per pixel.
        let value = timed(|| {
            for (y, row) in height.chunks_exact_mut(w).enumerate() {
                for (x, v) in row.iter_mut().enumerate() {
                    *v = noise.get_noise_2d(x as f32, y as f32);
                }
            }
            black_box(&height);
        });
        // Value and normal by central differences on a grid one pixel wider on every side.
        let gridded = timed(|| on_grid(&noise, w, h, &mut grid, &mut height, &mut normals));
        // Value and normal pointwise: four more evaluations per pixel.
        let pointwise = timed(|| {
            for y in 0..h {
                for x in 0..w {
                    let (fx, fy) = (x as f32, y as f32);
                    height[y * w + x] = noise.get_noise_2d(fx, fy);
                    let dx = 0.5 * (noise.get_noise_2d(fx + 1.0, fy) - noise.get_noise_2d(fx - 1.0, fy));
                    let dy = 0.5 * (noise.get_noise_2d(fx, fy + 1.0) - noise.get_noise_2d(fx, fy - 1.0));
                    normals[y * w + x] = normal(dx, dy);
                }
            }
            black_box((&height, &normals));
        });
        // Three octaves a third apart, as our three levels are; normal from the grid.
        let gridded3 = timed(|| on_grid(&octaves, w, h, &mut grid, &mut height, &mut normals));

        if round > 0 {
            for (list, t) in times.iter_mut().zip([
                built,
                total - built,
                total,
                value,
                gridded,
                pointwise,
                gridded3,
                height_only,
                normal_only,
            ]) {
                list.push(t);
            }
        }
    }
    let [build, render, total, value, gridded, pointwise, gridded3, height_only, normal_only] = times.map(median);
    let load = [load, load_average()];

    let ratio = |d: Duration| total.as_secs_f64() / d.as_secs_f64();
    println!(
        "| {w}×{h}, fig19a ({} levels, {cell_count} cells), height + normal; median of {RUNS} runs | time | ours (total) ÷ it |",
        params.levels
    );
    println!("|---|---|---|");
    println!("| hibi Model C: build (`Skin::new` + `run`) | {:.2} ms | |", ms(build));
    println!("| hibi Model C: render height + normal | {:.2} ms | |", ms(render));
    println!("| hibi Model C: total | {:.2} ms | |", ms(total));
    println!("| hibi Model C: render height alone | {:.2} ms | |", ms(height_only));
    println!("| hibi Model C: render normal alone | {:.2} ms | |", ms(normal_only));
    println!(
        "| FastNoiseLite Distance2Sub, 1/{SPACING} px⁻¹: value per pixel | {:.2} ms | {:.2}× |",
        ms(value),
        ratio(value)
    );
    println!(
        "| FastNoiseLite: value + normal by central differences on its {gw}×{gh} value grid | {:.2} ms | {:.2}× |",
        ms(gridded),
        ratio(gridded)
    );
    println!(
        "| FastNoiseLite: value + normal pointwise (4 extra evaluations per pixel) | {:.2} ms | {:.2}× |",
        ms(pointwise),
        ratio(pointwise)
    );
    println!(
        "| FastNoiseLite, 3 octaves (FBm, lacunarity 3): value + normal by central differences on its grid | {:.2} ms | {:.2}× |",
        ms(gridded3),
        ratio(gridded3)
    );
    let part = |d: Duration| 100.0 * d.as_secs_f64() / (build + render).as_secs_f64();
    let tables = format!(
        "| FastNoiseLite variant, {w}×{h} | hibi's time ÷ it |\n|---|---|\n\
         | value per pixel, one octave | {:.2}× |\n\
         | value and normal by central differences on its {gw} × {gh} value grid | {:.2}× |\n\
         | value and normal pointwise (four extra evaluations per pixel) | {:.2}× |\n\
         | three octaves (FBm, lacunarity 3) and the normal from its grid | {:.2}× |\n\n\
         How hibi's own time splits:\n\n\
         | hibi's time (medians taken apart) | share |\n|---|---|\n\
         | the build (`Skin::new` and `run`: {cell_count} cells) | {:.0} % |\n\
         | the render of both maps | {:.0} % |\n",
        ratio(value),
        ratio(gridded),
        ratio(pointwise),
        ratio(gridded3),
        part(build),
        part(render)
    );
    write_bench_tables("bench-skin.md", "cargo bench --bench skin", load, &tables);
}
