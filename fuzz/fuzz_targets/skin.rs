//! Model C through the C ABI: params from the input, `hibi_skin_create` or
//! `hibi_skin_create_in` (any memory length and alignment), then any sequence of steps (any
//! budgets), cell queries and outlines (any lengths), renders (any layer, length and cell
//! level) and shading of what was rendered.
#![no_main]

use arbitrary::{Result, Unstructured};
use hibi::*;
use hibi_fuzz::*;
use libfuzzer_sys::fuzz_target;

const WRITTEN: usize = usize::MAX - 3;

struct Surface {
    skin: *mut hibi_skin,
    params: hibi_skin_params,
    work: u64,
    finished: bool,
}

fn step(u: &mut Unstructured, s: &mut Surface) -> Result<()> {
    let mut budget = budget(u)?;
    if !s.finished {
        budget = budget.min(MAX_WORK.saturating_sub(s.work));
    }
    let mut progress = hibi_skin_progress { finished: u32::MAX, work: u64::MAX, ..Default::default() };
    let o = out(u, &mut progress)?;
    // SAFETY: a live skin; `o` NULL or writable.
    let status = unsafe { hibi_skin_step(s.skin, budget, o) };
    if check(status) {
        if !o.is_null() {
            assert!(progress.finished <= 1 && progress.capacity_reached <= 1, "{progress:?}");
            assert!(progress.roots <= progress.root_total, "{progress:?}");
            assert!(progress.work >= s.work, "work went back");
            s.work = progress.work;
            s.finished = progress.finished == 1;
        }
    } else {
        assert_eq!(status, HIBI_ERROR_SKIN_CAPACITY);
        assert_eq!(progress.finished, u32::MAX, "a failing step wrote");
        s.finished = true;
    }
    Ok(())
}

fn cell(u: &mut Unstructured, s: &Surface) -> Result<()> {
    let mut count = WRITTEN;
    // SAFETY: a live skin, a writable count.
    assert!(check(unsafe { hibi_skin_cell_count(s.skin, &mut count) }));
    let index = if u.ratio(1u8, 8)? { u.arbitrary()? } else { u.int_in_range(0..=count)? };
    let mut info = hibi_skin_cell { level: u32::MAX, ..Default::default() };
    // SAFETY: a live skin, a writable cell.
    let status = unsafe { hibi_skin_cell_info(s.skin, index, &mut info) };
    if check(status) {
        assert!(index < count && info.level < s.params.levels, "{info:?}");
        assert_eq!(info.parent == HIBI_SKIN_NO_CELL, info.level == 0, "{info:?}");
        assert!(info.parent == HIBI_SKIN_NO_CELL || (info.parent as usize) < index, "{info:?}");
        assert!(info.centre.iter().all(|c| c.is_finite()), "{info:?}");
    } else {
        assert!(status == HIBI_ERROR_SKIN_CELL_INDEX && index >= count && info.level == u32::MAX);
    }
    let need = if status == HIBI_OK { 2 * info.vertex_count as usize } else { 8 };
    let mut xy = Buffer::pick(u, need, need + 8, 8)?;
    let mut written = WRITTEN;
    let w = out(u, &mut written)?;
    // SAFETY: `xy` NULL or writable for its length.
    let status = unsafe { hibi_skin_outline(s.skin, index, xy.ptr(), xy.len, w) };
    let (possible, required) = xy.fits(need, 8);
    let valid = index < count && !w.is_null();
    if check(status) {
        assert!(valid && possible && written == need);
        assert!(xy.untouched_past(need));
        assert!((0..need).all(|i| xy.get::<f64>(i).is_finite()), "an outline point not finite");
    } else {
        assert!(!(valid && required), "outline refused a buffer that fits: {status}");
        assert!(xy.untouched() && written == WRITTEN, "a failing call wrote");
    }
    Ok(())
}

fn render(u: &mut Unstructured, s: &Surface) -> Result<()> {
    let pixels = s.params.width as usize * s.params.height as usize;
    let render = hibi_skin_render_params { cell_level: count(u, 0..=4)?, ..hibi_skin_render_params_default() };
    let layer = enumeration(u, 3)?;
    // Values per pixel (floats for the normal layer); each value is 4 bytes.
    let per = if layer == HIBI_SKIN_LAYER_NORMAL { 3 } else { 1 };
    let need = per * pixels;
    let mut out = Buffer::pick(u, need, need + 8, 4)?;
    let rp: *const hibi_skin_render_params = if u.ratio(1u8, 48)? { core::ptr::null() } else { &render };
    // SAFETY: `out` NULL or writable for its length.
    let status = unsafe { hibi_skin_render(s.skin, rp, layer, out.ptr(), out.len) };
    let (possible, required) = out.fits(need, 4);
    let level_ok = layer != HIBI_SKIN_LAYER_CELLS || render.cell_level < s.params.levels;
    let valid = !rp.is_null() && layer < 3 && level_ok;
    if check(status) {
        assert!(valid && possible, "render accepted layer {layer}, level {}, {} values", render.cell_level, out.len);
        assert!(out.untouched_past(need));
        match layer {
            HIBI_SKIN_LAYER_HEIGHT => {
                assert!((0..pixels).all(|i| out.get::<f32>(i).is_finite()), "a height not finite");
            }
            HIBI_SKIN_LAYER_NORMAL => {
                for i in 0..pixels {
                    let v = [out.get::<f32>(3 * i), out.get::<f32>(3 * i + 1), out.get::<f32>(3 * i + 2)];
                    let length = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
                    assert!(finite(&v) && (length - 1.0).abs() < 1e-3, "normal {v:?} not unit");
                }
                if u.arbitrary()? {
                    // The heights beside these normals, then shading them.
                    let mut height = Buffer::new(pixels, 4, 0, false);
                    // SAFETY: `height` writable for `pixels` floats.
                    let status =
                        unsafe { hibi_skin_render(s.skin, &render, HIBI_SKIN_LAYER_HEIGHT, height.ptr(), pixels) };
                    assert!(check(status), "the height layer beside an accepted normal layer: {status}");
                    shade(u, &height, &out, pixels)?;
                }
            }
            _ => {
                let mut cells = 0;
                // SAFETY: a live skin, a writable count.
                assert!(check(unsafe { hibi_skin_cell_count(s.skin, &mut cells) }));
                assert!((0..pixels).all(|i| {
                    let c = out.get::<u32>(i);
                    c == HIBI_SKIN_NO_CELL || (c as usize) < cells
                }));
            }
        }
    } else {
        assert!(
            !(valid && required),
            "render refused what fits: {status} (layer {layer}, level {}, {} values); params {:?}",
            render.cell_level,
            out.len,
            s.params
        );
        assert!(out.untouched(), "a failing render wrote");
    }
    Ok(())
}

/// Shades rendered maps (the `shade` target shades arbitrary ones).
fn shade(u: &mut Unstructured, height: &Buffer, normal: &Buffer, pixels: usize) -> Result<()> {
    let h: Vec<f32> = (0..pixels).map(|i| height.get(i)).collect();
    let n: Vec<f32> = (0..3 * pixels).map(|i| normal.get(i)).collect();
    let params = hibi_skin_shade_params_default();
    let mut rgb = Buffer::pick(u, 3 * pixels, 3 * pixels + 8, 1)?;
    // SAFETY: the inputs are readable for their lengths, `rgb` writable for its length.
    let status = unsafe { hibi_skin_shade(h.as_ptr(), h.len(), n.as_ptr(), n.len(), &params, rgb.ptr(), rgb.len) };
    let (possible, required) = rgb.fits(3 * pixels, 1);
    if check(status) {
        assert!(possible && rgb.untouched_past(3 * pixels));
    } else {
        assert!(!required, "shade refused what fits: {status}");
        assert!(rgb.untouched());
    }
    Ok(())
}

fn run(u: &mut Unstructured) -> Result<()> {
    let params = skin_params(u)?;
    let made =
        create(u, &params, hibi_skin_memory_size, hibi_skin_memory_align, hibi_skin_create, hibi_skin_create_in)?;
    let Some((skin, memory)) = made else { return Ok(()) };
    let mut surface = Surface { skin, params, work: 0, finished: false };
    let result = (|| {
        for _ in 0..10 {
            match u.int_in_range(0u8..=4)? {
                0 | 1 => step(u, &mut surface)?,
                2 | 3 => cell(u, &surface)?,
                _ => render(u, &surface)?,
            }
        }
        Ok(())
    })();
    if memory.is_empty() || u.arbitrary().unwrap_or(true) {
        // SAFETY: a live skin, not used afterwards.
        unsafe { hibi_skin_destroy(skin) };
    }
    drop(memory);
    result
}

fuzz_target!(|data: &[u8]| {
    let _ = run(&mut Unstructured::new(data));
});
