//! Model A through the C ABI: params from the input, `hibi_mud_create` or
//! `hibi_mud_create_in` (any memory length and alignment), then any sequence of steps (any
//! budgets), segment, network and cell outputs (any buffer lengths), statistics and renders
//! (every layer, any render params and pixel lengths). A finished periodic run's cells cover
//! the plate: their signed areas add up to its area, unless a region wraps around it.
#![no_main]

use core::ptr::null;

use arbitrary::{Result, Unstructured};
use hibi::*;
use hibi_core::polygon::Ring;
use hibi_core::mud::{CrackSegment, NetworkEdge, NetworkPoint, NetworkVertex};
use hibi_fuzz::*;
use libfuzzer_sys::fuzz_target;

const WRITTEN: usize = usize::MAX - 3;

/// Where the run stands, as the step calls reported it.
struct Run {
    work: u64,
    finished: bool,
    /// The misfit at the last report.
    shrink: f32,
    /// The status every step returns once the built lattice was refused.
    refused: Option<hibi_status>,
}

fn step(u: &mut Unstructured, mud: *mut hibi_mud, p: &hibi_mud_params, run: &mut Run) -> Result<()> {
    let mut budget = budget(u)?;
    if !run.finished {
        budget = budget.min(MAX_WORK.saturating_sub(run.work));
    }
    let mut progress = hibi_mud_progress { work: u64::MAX, ..Default::default() };
    let out = out(u, &mut progress)?;
    // SAFETY: a live run; `out` NULL or writable.
    let status = unsafe { hibi_mud_step(mud, budget, out) };
    if let Some(refused) = run.refused {
        assert_eq!(status, refused, "a refused run stepped on");
        assert_eq!(progress.work, u64::MAX, "a refused step wrote its progress");
        return Ok(());
    }
    if status == HIBI_ERROR_MUD_SHORT_STEP_STABILITY {
        // Only the irregular lattice's explicit run is checked on its built mesh, by the step
        // that finishes building it.
        assert!(p.topology == HIBI_MUD_IRREGULAR && p.solver == HIBI_MUD_EXPLICIT, "{p:?}");
        assert_eq!(progress.work, u64::MAX, "a refused step wrote its progress");
        run.refused = Some(status);
        return Ok(());
    }
    assert!(check(status), "step failed: {status}");
    if !out.is_null() {
        assert!(progress.work >= run.work, "work went back");
        run.work = progress.work;
        run.finished = progress.finished == 1;
        run.shrink = progress.shrink;
        assert!(progress.finished <= 1);
        assert!(finite(&[progress.shrink, progress.time, progress.crack_density]), "{progress:?}");
    }
    Ok(())
}

fn segments(u: &mut Unstructured, mud: *mut hibi_mud) -> Result<()> {
    let mut count = WRITTEN;
    // SAFETY: a live run, a writable count.
    assert!(check(unsafe { hibi_mud_segment_count(mud, &mut count) }));
    let mut buffer = Buffer::pick(u, count, count + 8, size_of::<CrackSegment>())?;
    let mut written = WRITTEN;
    let w = out(u, &mut written)?;
    // SAFETY: `buffer` is NULL or writable for its length.
    let status = unsafe { hibi_mud_segments(mud, buffer.ptr(), buffer.len, w) };
    let (possible, required) = buffer.fits(count, 4);
    let (possible, required) = (possible && !w.is_null(), required && !w.is_null());
    if check(status) {
        assert!(possible && written == count);
        assert!(buffer.untouched_past(count));
        for i in 0..count {
            let s: CrackSegment = buffer.get(i);
            assert!(
                finite(&[s.start[0], s.start[1], s.end[0], s.end[1], s.width[0], s.width[1]]),
                "{s:?}; params {}",
                LAST.with(|l| l.borrow().clone())
            );
            assert!(finite(&s.time), "{s:?}");
        }
    } else {
        assert!(!required, "segments refused a buffer that fits: {status}");
        assert!(buffer.untouched() && written == WRITTEN, "a failing call wrote");
    }
    Ok(())
}

fn network(u: &mut Unstructured, mud: *mut hibi_mud) -> Result<()> {
    let (mut v, mut e, mut p) = (WRITTEN, WRITTEN, WRITTEN);
    // SAFETY: a live run, writable counts.
    assert!(check(unsafe { hibi_mud_network_counts(mud, &mut v, &mut e, &mut p) }));
    let mut vb = Buffer::pick(u, v, v + 8, size_of::<NetworkVertex>())?;
    let mut eb = Buffer::pick(u, e, e + 8, size_of::<NetworkEdge>())?;
    let mut pb = Buffer::pick(u, p, p + 8, size_of::<NetworkPoint>())?;
    let (mut vw, mut ew, mut pw) = (WRITTEN, WRITTEN, WRITTEN);
    let (vo, eo, po) = (out(u, &mut vw)?, out(u, &mut ew)?, out(u, &mut pw)?);
    // SAFETY: buffers NULL or writable for their lengths.
    let status = unsafe { hibi_mud_network(mud, vb.ptr(), vb.len, eb.ptr(), eb.len, pb.ptr(), pb.len, vo, eo, po) };
    let outs = !vo.is_null() && !eo.is_null() && !po.is_null();
    let [a, b, c] = [vb.fits(v, 4), eb.fits(e, 4), pb.fits(p, 4)];
    let (possible, required) = (outs && a.0 && b.0 && c.0, outs && a.1 && b.1 && c.1);
    if check(status) {
        assert!(possible && vw == v && ew == e && pw == p);
        assert!(vb.untouched_past(v) && eb.untouched_past(e) && pb.untouched_past(p));
        for i in 0..v {
            let x: NetworkVertex = vb.get(i);
            assert!(finite(&x.at) && x.on_border <= 1, "{x:?}");
        }
        for i in 0..e {
            let x: NetworkEdge = eb.get(i);
            assert!(x.from == HIBI_MUD_NO_VERTEX || (x.from as usize) < v, "{x:?}");
            assert!(x.to == HIBI_MUD_NO_VERTEX || (x.to as usize) < v, "{x:?}");
            assert!(x.first_point as usize + x.point_count as usize <= p, "{x:?}");
        }
        for i in 0..p {
            let x: NetworkPoint = pb.get(i);
            assert!(finite(&[x.at[0], x.at[1], x.width, x.time]), "{x:?}");
        }
    } else {
        assert!(!required, "network refused buffers that fit: {status}");
        assert!(vb.untouched() && eb.untouched() && pb.untouched(), "a failing call wrote");
        assert!(vw == WRITTEN && ew == WRITTEN && pw == WRITTEN, "a failing call wrote a count");
    }
    Ok(())
}

fn cells(u: &mut Unstructured, mud: *mut hibi_mud, params: &hibi_mud_params, run: &Run) -> Result<()> {
    let (mut r, mut p, mut wrapping) = (WRITTEN, WRITTEN, WRITTEN);
    // SAFETY: a live run, writable counts.
    assert!(check(unsafe { hibi_mud_cell_counts(mud, &mut r, &mut p, &mut wrapping) }));
    let mut rb = Buffer::pick(u, r, r + 8, size_of::<Ring>())?;
    let mut pb = Buffer::pick(u, p, p + 8, size_of::<hibi_vec2>())?;
    let (mut rw, mut pw) = (WRITTEN, WRITTEN);
    let (ro, po) = (out(u, &mut rw)?, out(u, &mut pw)?);
    // SAFETY: buffers NULL or writable for their lengths.
    let status = unsafe { hibi_mud_cells(mud, rb.ptr(), rb.len, pb.ptr(), pb.len, ro, po) };
    let outs = !ro.is_null() && !po.is_null();
    let [a, b] = [rb.fits(r, 8), pb.fits(p, 4)];
    let (possible, required) = (outs && a.0 && b.0, outs && a.1 && b.1);
    if check(status) {
        assert!(possible && rw == r && pw == p);
        assert!(rb.untouched_past(r) && pb.untouched_past(p));
        let (mut covered, mut wraps) = (0.0f64, wrapping > 0);
        for i in 0..r {
            let x: Ring = rb.get(i);
            assert!(x.area.is_finite() && x.first_point as usize + x.point_count as usize <= p, "{x:?}");
            assert_eq!(x.reserved, 0, "{x:?}");
            covered += x.area;
            // An outer ring of positive area; a hole of negative area in a ring, or in a cell that
            // wraps around a periodic lattice.
            let in_wrapping = x.hole_of == HIBI_MUD_IN_WRAPPING_CELL && x.area < 0.0;
            wraps |= in_wrapping;
            let in_ring = (x.hole_of as usize) < r && x.area < 0.0;
            assert!((x.hole_of == HIBI_RING_NOT_A_HOLE && x.area > 0.0) || in_ring || in_wrapping, "{x:?}");
        }
        for i in 0..p {
            let x: hibi_vec2 = pb.get(i);
            assert!(finite(&[x.x, x.y]), "{x:?}");
        }
        // A finished periodic run's cells cover one period of the plate (drawn in the
        // growing frame under the growth drive), unless a region wraps around it.
        if run.finished && params.boundary == HIBI_MUD_PERIODIC && !wraps && r > 0 {
            let mut extent = hibi_vec2 { x: f32::NAN, y: f32::NAN };
            // SAFETY: a live run, a writable extent.
            assert!(check(unsafe { hibi_mud_extent(mud, &mut extent) }));
            let [w, h] = [extent.x, extent.y];
            let deep = if params.drive == HIBI_MUD_GROWTH { 1.0 + run.shrink } else { 1.0 };
            let plate = f64::from(w * deep) * f64::from(h * deep);
            assert!(((covered - plate) / plate).abs() <= 1e-4, "cells cover {covered} of a {plate} plate ({r} rings)");
        }
    } else {
        assert!(!required, "cells refused buffers that fit: {status}");
        assert!(rb.untouched() && pb.untouched() && rw == WRITTEN && pw == WRITTEN, "a failing call wrote");
    }
    Ok(())
}

fn measure(u: &mut Unstructured, mud: *mut hibi_mud) -> Result<()> {
    let mut s = hibi_mud_crack_statistics { cells: u32::MAX, ..Default::default() };
    let o = out(u, &mut s)?;
    // SAFETY: a live run; `o` NULL or writable.
    let status = unsafe { hibi_mud_statistics(mud, o) };
    if check(status) {
        assert!(
            finite(&[s.crack_density, s.mean_cell_area, s.cell_area_spread, s.mean_widest_junction_angle]),
            "{s:?}"
        );
    } else {
        assert!(o.is_null() && s.cells == u32::MAX);
    }
    Ok(())
}

fn render(u: &mut Unstructured, mud: *mut hibi_mud) -> Result<()> {
    let mut r = hibi_mud_render_params_default();
    r.width = count(u, 0..=64)?;
    r.height = count(u, 0..=64)?;
    r.width_scale = float(u, r.width_scale)?;
    r.min_width = float(u, r.min_width)?;
    r.groove_depth = float(u, r.groove_depth)?;
    r.offset = [float(u, r.offset[0])?, float(u, r.offset[1])?];
    let layer = enumeration(u, 3)?;
    let size = if layer == HIBI_MUD_LAYER_MASK { 1 } else { 4 };
    let need = (r.width as usize).saturating_mul(r.height as usize);
    let mut pixels = Buffer::pick(u, need.min(MAX_PIXELS), MAX_PIXELS, size)?;
    let rp: *const hibi_mud_render_params = if u.ratio(1u8, 48)? { null() } else { &r };
    // SAFETY: `pixels` NULL or writable for its length.
    let status = unsafe { hibi_mud_render(mud, rp, layer, pixels.ptr(), pixels.len) };
    let valid = |x: f32| x.is_finite() && x >= 0.0;
    let (possible, required) = pixels.fits(need, size);
    let valid_params = !rp.is_null()
        && need > 0
        && layer < 3
        && valid(r.width_scale)
        && valid(r.min_width)
        && valid(r.groove_depth)
        && finite(&r.offset);
    if check(status) {
        assert!(valid_params && possible, "render accepted {r:?}, layer {layer}, {} pixels", pixels.len);
        assert!(pixels.untouched_past(need));
        if layer == HIBI_MUD_LAYER_HEIGHT {
            assert!((0..need).all(|i| pixels.get::<f32>(i).is_finite()), "a height not finite");
        } else if layer == HIBI_MUD_LAYER_TIME {
            assert!(
                (0..need).all(|i| {
                    let t = pixels.get::<f32>(i);
                    t.is_finite() || t == f32::INFINITY
                }),
                "a time neither finite nor +inf"
            );
        }
    } else {
        assert!(!(valid_params && required), "render refused {r:?}, layer {layer}, {} pixels: {status}", pixels.len);
        assert!(pixels.untouched(), "a failing render wrote");
    }
    Ok(())
}

fn run(u: &mut Unstructured) -> Result<()> {
    let p = mud_params(u)?;
    let made = create(u, &p, hibi_mud_memory_size, hibi_mud_memory_align, hibi_mud_create, hibi_mud_create_in)?;
    let Some((mud, memory)) = made else { return Ok(()) };
    let mut run = Run { work: 0, finished: false, shrink: 0.0, refused: None };
    let result = (|| {
        for _ in 0..12 {
            match u.int_in_range(0u8..=5)? {
                0 | 1 => step(u, mud, &p, &mut run)?,
                2 => segments(u, mud)?,
                3 => network(u, mud)?,
                4 => cells(u, mud, &p, &run)?,
                _ => {
                    if u.arbitrary()? {
                        measure(u, mud)?
                    } else {
                        render(u, mud)?
                    }
                }
            }
        }
        Ok(())
    })();
    if memory.is_empty() || u.arbitrary().unwrap_or(true) {
        // SAFETY: a live run, not used afterwards.
        unsafe { hibi_mud_destroy(mud) };
    }
    drop(memory);
    result
}

fuzz_target!(|data: &[u8]| {
    let _ = run(&mut Unstructured::new(data));
});
