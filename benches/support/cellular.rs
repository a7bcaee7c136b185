//! FastNoiseLite's cellular noise as Model C's benches compare with it (`benches/skin.rs`
//! times it, `tests/instructions.rs` counts it): Distance2Sub with Euclidean distances,
//! cells [`SPACING`] px wide, and a normal map by central differences on its value grid.

use std::hint::black_box;

use fastnoise_lite::{CellularDistanceFunction, CellularReturnType, FastNoiseLite, NoiseType};

/// Model C's level-1 spacing in pixels; FastNoiseLite's cells are 1/frequency pixels wide.
pub const SPACING: f32 = 40.0;

/// The unit normal (x right, y up, z out) of a height field with these central differences
/// (per pixel, image rows going down).
pub fn normal(dx: f32, dy_down: f32) -> [f32; 3] {
    let (nx, ny) = (-dx, dy_down);
    let r = 1.0 / (nx * nx + ny * ny + 1.0).sqrt();
    [nx * r, ny * r, r]
}

/// FastNoiseLite's cellular noise, Distance2Sub with Euclidean distances, cells `SPACING` wide.
pub fn cellular() -> FastNoiseLite {
    let mut noise = FastNoiseLite::with_seed(1);
    noise.set_noise_type(Some(NoiseType::Cellular));
    noise.set_cellular_distance_function(Some(CellularDistanceFunction::Euclidean));
    noise.set_cellular_return_type(Some(CellularReturnType::Distance2Sub));
    noise.set_frequency(Some(1.0 / SPACING));
    noise
}

/// Value and normal of `noise` for a `w`×`h` image, by central differences on `grid`, a value
/// grid one pixel wider on every side ((w + 2)·(h + 2) evaluations).
pub fn on_grid(
    noise: &FastNoiseLite,
    w: usize,
    h: usize,
    grid: &mut [f32],
    height: &mut [f32],
    normals: &mut [[f32; 3]],
) {
    let gw = w + 2;
    for (gy, row) in grid.chunks_exact_mut(gw).enumerate() {
        for (gx, v) in row.iter_mut().enumerate() {
            *v = noise.get_noise_2d(gx as f32 - 1.0, gy as f32 - 1.0);
        }
    }
    for y in 0..h {
        for x in 0..w {
            let g = |dx: usize, dy: usize| grid[(y + dy) * gw + x + dx];
            height[y * w + x] = g(1, 1);
            normals[y * w + x] = normal(0.5 * (g(2, 1) - g(0, 1)), 0.5 * (g(1, 2) - g(1, 0)));
        }
    }
    black_box((height, normals));
}
