//! The reference for `python/bench.py`'s overhead figure: the work one Python call sequence
//! does (build a model, run it to its end, render its crack mask), straight through
//! hibi-core's Rust API, with no Python objects in between. Exposed as
//! `hibi._hibi._reference(scene)` so that the bench times both in one process, alternated.

use pyo3::prelude::*;

use hibi_core::glass::{Glass, GlassLayers, GlassParams, GlassRender};
use hibi_core::mud::{Mud, MudLayers, MudParams, MudRender};
use hibi_core::raster::scratch_len;

/// The default mud lattice with rows making its domain square, drawn 256 × 256.
fn mud256() {
    let p = MudParams { rows: 148, ..MudParams::default() };
    let mut store = p.memory().expect("valid").allocate::<f32>();
    let mut mud = Mud::new(&p, store.buffers()).expect("memory of the size asked for");
    mud.run().expect("a run of valid parameters");
    let r = MudRender { width: 256, height: 256, ..MudRender::fit(mud.extent(), 256) };
    let mut mask = vec![0u8; 256 * 256];
    let mut scratch = vec![0u32; scratch_len(256, 256).expect("small")];
    let layers = MudLayers { mask: Some(&mut mask), scratch: Some(&mut scratch), ..MudLayers::default() };
    mud.render(&r, layers).expect("a valid view");
    std::hint::black_box(&mask);
}

/// The paper's default plate, 640 × 640, one pixel per px.
fn glass640() {
    let p = GlassParams::default();
    let mut store = p.memory().expect("valid").allocate();
    let mut glass = Glass::new(&p, store.buffers()).expect("memory of the size asked for");
    while !glass.step(u64::MAX).finished {}
    let r = GlassRender::default();
    let mut mask = vec![0u8; 640 * 640];
    let mut scratch = vec![0u32; scratch_len(640, 640).expect("small")];
    let layers = GlassLayers { mask: Some(&mut mask), scratch: Some(&mut scratch), ..GlassLayers::default() };
    glass.render(&r, layers).expect("a valid raster");
    std::hint::black_box(&mask);
}

/// Runs the reference scene `scene` ("mud256" or "glass640") with the GIL released.
#[pyfunction]
pub fn _reference(py: Python<'_>, scene: &str) -> PyResult<()> {
    let f: fn() = match scene {
        "mud256" => mud256,
        "glass640" => glass640,
        _ => return Err(crate::value_error("_reference: scene must be mud256 or glass640")),
    };
    py.detach(f);
    Ok(())
}
