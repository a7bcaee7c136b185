//! The browser bench's native side: each case of web/bench/bench.js (the same parameters,
//! the same budgets, the same layers) generated and rendered `RUNS` times on the host; prints
//! one JSON object per case with the median milliseconds.

use std::time::Instant;

use hibi_core::glass::{Glass, GlassLayers, GlassParams, GlassRender};
use hibi_core::mud::{Mud, MudLayers, MudParams, MudRender};
use hibi_core::raster::scratch_len;
use hibi_core::skin::{Skin, SkinLayers, SkinRender};

const RUNS: usize = 5;
/// Work per step, as bench.js steps.
const BUDGET: u64 = 1_000_000_000;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1000.0
}

fn report(case: &str, generate: Vec<f64>, render: Vec<f64>) {
    println!("{{\"case\":\"{case}\",\"generate_ms\":{:.3},\"render_ms\":{:.3}}}", median(generate), median(render));
}

fn main() {
    let (mut generate, mut render) = (Vec::new(), Vec::new());
    for _ in 0..RUNS {
        let params = MudParams { columns: 96, rows: 96, ..hibi_core::mud::preset("fig6a").unwrap() };
        let t = Instant::now();
        let mut store = params.memory().unwrap().allocate::<f32>();
        let mut mud = Mud::new(&params, store.buffers()).unwrap();
        while !mud.step(BUDGET).unwrap().finished {}
        generate.push(ms(t));
        let view = MudRender::fit(mud.extent(), 512);
        let t = Instant::now();
        let n = (view.width * view.height) as usize;
        let mut preview = vec![[0u8; 4]; n];
        let mut scratch = vec![0u32; scratch_len(view.width, view.height).unwrap()];
        let layers = MudLayers { preview: Some(&mut preview), scratch: Some(&mut scratch), ..Default::default() };
        mud.render(&view, layers).unwrap();
        render.push(ms(t));
        std::hint::black_box(&preview);
    }
    report("mud fig6a 96² (render 512 px)", std::mem::take(&mut generate), std::mem::take(&mut render));
    for _ in 0..RUNS {
        let params = GlassParams::default();
        let t = Instant::now();
        let mut store = params.memory().unwrap().allocate();
        let mut glass = Glass::new(&params, store.buffers()).unwrap();
        while !glass.step(BUDGET).finished {}
        generate.push(ms(t));
        let view = GlassRender { width: 640, height: 640, ..GlassRender::default() };
        let t = Instant::now();
        let mut preview = vec![[0u8; 4]; 640 * 640];
        let mut scratch = vec![0u32; scratch_len(640, 640).unwrap()];
        let layers = GlassLayers { preview: Some(&mut preview), scratch: Some(&mut scratch), ..Default::default() };
        glass.render(&view, layers).unwrap();
        render.push(ms(t));
        std::hint::black_box(&preview);
    }
    report("glass defaults 640²", std::mem::take(&mut generate), std::mem::take(&mut render));
    for _ in 0..RUNS {
        let params = hibi_core::skin::preset("fig19a").unwrap();
        let t = Instant::now();
        let mut store = params.memory().unwrap().allocate();
        let mut skin: Skin = Skin::new(&params, store.buffers()).unwrap();
        while !skin.step(BUDGET).finished {}
        generate.push(ms(t));
        let t = Instant::now();
        let n = (params.width * params.height) as usize;
        let mut preview = vec![[0u8; 4]; n];
        let mut scratch = vec![0u32; scratch_len(params.width, params.height).unwrap()];
        let layers = SkinLayers { preview: Some(&mut preview), scratch: Some(&mut scratch), ..Default::default() };
        skin.render(&SkinRender::default(), layers).unwrap();
        render.push(ms(t));
        std::hint::black_box(&preview);
    }
    report("skin fig19a 400²", generate, render);
}
