//! Model B through the C ABI: params from the input, `hibi_glass_create` or
//! `hibi_glass_create_in` (any memory length and alignment), then any sequence of impacts
//! (any point), steps (any budgets), crack queries and polylines, fragments and fragment
//! counts (any scratch and buffer lengths) and renders (both layers, any render params and
//! pixel lengths). Fragments must cover the plate: their signed areas sum to its area, and so
//! do the areas of their convex pieces for a physics engine (`hibi_convex_pieces`).
#![no_main]

use core::ptr::null;

use arbitrary::{Result, Unstructured};
use hibi::*;
use hibi_core::glass::CrackPoint;
use hibi_core::polygon::Ring;
use hibi_fuzz::*;
use libfuzzer_sys::fuzz_target;

const WRITTEN: usize = usize::MAX - 3;

struct Plate {
    glass: *mut hibi_glass,
    width: f32,
    height: f32,
    /// Step calls left (each with a budget of at most `MAX_WORK / 8` unless generation ended).
    steps: u32,
    finished: bool,
}

fn impact(u: &mut Unstructured, g: &mut Plate) -> Result<()> {
    let [i, j] = [u.int_in_range(0u8..=8)?, u.int_in_range(0u8..=8)?];
    let x = float(u, g.width * f32::from(i) / 8.0)?;
    let y = float(u, g.height * f32::from(j) / 8.0)?;
    let mut counts = hibi_glass_counts { radial: u32::MAX, large: u32::MAX, rings: u32::MAX };
    let o = out(u, &mut counts)?;
    // SAFETY: a live plate; `o` NULL or writable.
    let status = unsafe { hibi_glass_impact(g.glass, x, y, o) };
    let inside = x > 0.0 && x < g.width && y > 0.0 && y < g.height;
    if check(status) {
        assert!(inside, "impact accepted ({x}, {y}) on a {} x {} plate", g.width, g.height);
        if !o.is_null() {
            assert!(counts.large <= counts.radial, "{counts:?}");
        }
        g.finished = false;
    } else if status == HIBI_ERROR_GLASS_CAPACITY {
        // Refused on a plate out of capacity: its steps say so too.
        assert_eq!(counts.radial, u32::MAX, "a failing impact wrote");
        // SAFETY: a live plate; no progress asked for.
        let step = unsafe { hibi_glass_step(g.glass, 1, core::ptr::null_mut()) };
        assert_eq!(step, HIBI_ERROR_GLASS_CAPACITY, "impact refused for capacity, but a step has room");
    } else {
        assert_eq!(status, HIBI_ERROR_GLASS_IMPACT);
        assert!(!inside, "impact refused ({x}, {y}) on a {} x {} plate", g.width, g.height);
        assert_eq!(counts.radial, u32::MAX, "a failing impact wrote");
    }
    Ok(())
}

fn step(u: &mut Unstructured, g: &mut Plate) -> Result<()> {
    let mut budget = budget(u)?;
    if g.steps == 0 {
        return Ok(());
    }
    g.steps -= 1;
    if !g.finished {
        budget = budget.min(MAX_WORK / 8);
    }
    let mut progress = hibi_glass_progress { finished: u32::MAX, ..Default::default() };
    let o = out(u, &mut progress)?;
    // SAFETY: a live plate; `o` NULL or writable.
    let status = unsafe { hibi_glass_step(g.glass, budget, o) };
    if check(status) {
        if !o.is_null() {
            assert!(progress.finished <= 1 && progress.capacity_reached <= 1, "{progress:?}");
            assert!(progress.growing <= progress.cracks, "{progress:?}");
            // Every impact's growth ends: it takes at most MAX_TIME_STEPS time steps.
            assert!(progress.time <= hibi_core::glass::MAX_TIME_STEPS, "{progress:?}");
            g.finished = progress.finished == 1;
        }
    } else {
        assert_eq!(status, HIBI_ERROR_GLASS_CAPACITY);
        assert_eq!(progress.finished, u32::MAX, "a failing step wrote");
        g.finished = true;
    }
    Ok(())
}

fn crack(u: &mut Unstructured, g: &Plate) -> Result<()> {
    let mut count = WRITTEN;
    // SAFETY: a live plate, a writable count.
    assert!(check(unsafe { hibi_glass_crack_count(g.glass, &mut count) }));
    let index = if u.ratio(1u8, 8)? { u.arbitrary()? } else { u.int_in_range(0..=count)? };
    let mut info = hibi_glass_crack { kind: u32::MAX, ..Default::default() };
    // SAFETY: a live plate, a writable crack.
    let status = unsafe { hibi_glass_crack_info(g.glass, index, &mut info) };
    if !check(status) {
        assert!(status == HIBI_ERROR_GLASS_CRACK_INDEX && index >= count && info.kind == u32::MAX);
    } else {
        assert!(index < count && info.kind <= 3 && info.end <= 4, "{info:?}");
    }
    let need = if status == HIBI_OK { info.points as usize } else { 4 };
    let mut points = Buffer::pick(u, need, need + 8, size_of::<CrackPoint>())?;
    let mut written = WRITTEN;
    let w = out(u, &mut written)?;
    // SAFETY: `points` NULL or writable for its length.
    let status = unsafe { hibi_glass_points(g.glass, index, points.ptr(), points.len, w) };
    let (possible, required) = points.fits(need, 4);
    let valid = index < count && !w.is_null();
    if check(status) {
        assert!(valid && possible && written == need);
        assert!(points.untouched_past(need));
        for i in 0..need {
            let p: CrackPoint = points.get(i);
            assert!(finite(&[p.at[0], p.at[1], p.time]), "{p:?}; params {}", LAST.with(|l| l.borrow().clone()));
            assert!(
                p.at[0] >= 0.0 && p.at[0] <= g.width && p.at[1] >= 0.0 && p.at[1] <= g.height,
                "{p:?} off the plate"
            );
        }
    } else {
        assert!(!(valid && required), "points refused a buffer that fits: {status}");
        assert!(points.untouched() && written == WRITTEN, "a failing call wrote");
    }
    Ok(())
}

/// A scratch of about `hibi_glass_scratch_size` bytes (any length and alignment).
fn scratch(u: &mut Unstructured, g: &Plate) -> Result<(Buffer, usize)> {
    let mut size = WRITTEN;
    // SAFETY: a live plate, a writable size.
    assert!(check(unsafe { hibi_glass_scratch_size(g.glass, &mut size) }));
    Ok((Buffer::pick(u, size, size + 64, 1)?, size))
}

fn fragments(u: &mut Unstructured, g: &Plate) -> Result<()> {
    let (mut s, need) = scratch(u, g)?;
    let (mut r, mut p) = (WRITTEN, WRITTEN);
    // SAFETY: `s` NULL or writable for its length.
    let status = unsafe { hibi_glass_fragment_counts(g.glass, s.ptr(), s.len, &mut r, &mut p) };
    let scratch_fits = s.fits(need, 8);
    if !check(status) {
        assert!(!scratch_fits.1, "fragment_counts refused a scratch that fits: {status}");
        assert!(r == WRITTEN && p == WRITTEN, "a failing call wrote");
        return Ok(());
    }
    assert!(scratch_fits.0, "fragment_counts accepted a scratch that does not fit");
    let mut rb = Buffer::pick(u, r, r + 8, size_of::<Ring>())?;
    let mut pb = Buffer::pick(u, p, p + 8, size_of::<hibi_vec2>())?;
    let (mut rw, mut pw) = (WRITTEN, WRITTEN);
    let (ro, po) = (out(u, &mut rw)?, out(u, &mut pw)?);
    // SAFETY: buffers NULL or writable for their lengths; the scratch is ours.
    let status = unsafe { hibi_glass_fragments(g.glass, s.ptr(), s.len, rb.ptr(), rb.len, pb.ptr(), pb.len, ro, po) };
    let outs = !ro.is_null() && !po.is_null();
    let [a, b] = [rb.fits(r, 8), pb.fits(p, 4)];
    if check(status) {
        assert!(outs && a.0 && b.0 && rw == r && pw == p);
        assert!(rb.untouched_past(r) && pb.untouched_past(p));
        let mut covered = 0.0f64;
        for i in 0..r {
            let x: Ring = rb.get(i);
            assert!(x.area.is_finite() && x.first_point as usize + x.point_count as usize <= p, "{x:?}");
            assert!(x.hole_of == HIBI_RING_NOT_A_HOLE || (x.hole_of as usize) < r, "{x:?}");
            assert_eq!(x.reserved, 0, "{x:?}");
            covered += x.area;
        }
        // The fragments cover the plate, whatever the cracks so far: outer rings add their
        // area, holes take theirs off.
        let plate = f64::from(g.width) * f64::from(g.height);
        assert!(((covered - plate) / plate).abs() <= 1e-4, "fragments cover {covered} of a {plate} plate ({r} rings)");
        let mut points = Vec::with_capacity(p);
        for i in 0..p {
            let x: hibi_vec2 = pb.get(i);
            assert!(finite(&[x.x, x.y]), "{x:?}");
            points.push(x);
        }
        let rings: Vec<Ring> = (0..r).map(|i| rb.get(i)).collect();
        pieces_cover(&rings, &points, plate);
    } else {
        assert!(!(outs && a.1 && b.1), "fragments refused buffers that fit: {status}");
        assert!(rb.untouched() && pb.untouched() && rw == WRITTEN && pw == WRITTEN, "a failing call wrote");
    }
    Ok(())
}

/// The fragments' convex pieces for a physics engine cover the plate too, each of 3 to 8
/// points.
fn pieces_cover(rings: &[Ring], points: &[hibi_vec2], plate: f64) {
    let (rp, pp) = (rings.as_ptr(), points.as_ptr());
    let (mut words, mut triangles, mut pieces, mut written) = (0, 0, 0, 0);
    // SAFETY: valid buffers of the lengths passed.
    assert!(check(unsafe { hibi_pieces_scratch_size(rp, rings.len(), pp, points.len(), &mut words) }));
    let mut s = vec![0u32; words];
    // SAFETY: as above; the scratch holds `words` words.
    let status = unsafe {
        hibi_pieces_counts(rp, rings.len(), pp, points.len(), s.as_mut_ptr(), words, &mut triangles, &mut pieces)
    };
    assert!(check(status));
    let mut out = vec![hibi_core::polygon::ConvexPiece::default(); pieces];
    let (sp, op) = (s.as_mut_ptr(), out.as_mut_ptr());
    // SAFETY: as above; `out` holds `pieces` entries.
    let status = unsafe { hibi_convex_pieces(rp, rings.len(), pp, points.len(), sp, words, op, pieces, &mut written) };
    assert!(check(status) && written == pieces && pieces <= triangles);
    let mut covered = 0.0f64;
    for piece in &out {
        let n = piece.point_count as usize;
        assert!((3..=8).contains(&n), "{piece:?}");
        for k in 0..n {
            let (a, b) = (points[piece.points[k] as usize], points[piece.points[(k + 1) % n] as usize]);
            covered += 0.5 * (f64::from(a.x) * f64::from(b.y) - f64::from(b.x) * f64::from(a.y));
        }
    }
    assert!(((covered - plate) / plate).abs() <= 1e-4, "pieces cover {covered} of a {plate} plate");
}

fn render(u: &mut Unstructured, g: &Plate) -> Result<()> {
    let mut r = hibi_glass_render_params_default();
    r.width = count(u, 0..=64)?;
    r.height = count(u, 0..=64)?;
    r.line_width = float(u, r.line_width)?;
    let layer = enumeration(u, 2)?;
    let size = if layer == HIBI_GLASS_LAYER_MASK { 1 } else { 4 };
    let need = (r.width as usize).saturating_mul(r.height as usize);
    let mut pixels = Buffer::pick(u, need.min(MAX_PIXELS), MAX_PIXELS, size)?;
    let rp: *const hibi_glass_render_params = if u.ratio(1u8, 48)? { null() } else { &r };
    // SAFETY: `pixels` NULL or writable for its length.
    let status = unsafe { hibi_glass_render(g.glass, rp, layer, pixels.ptr(), pixels.len) };
    let (possible, required) = pixels.fits(need, size);
    let valid = !rp.is_null() && need > 0 && layer < 2 && r.line_width.is_finite() && r.line_width > 0.0;
    if check(status) {
        assert!(valid && possible, "render accepted {r:?}, layer {layer}, {} pixels", pixels.len);
        assert!(pixels.untouched_past(need));
        if layer == HIBI_GLASS_LAYER_TIME {
            let time = |i| pixels.get::<f32>(i);
            assert!(
                (0..need).all(|i| time(i).is_finite() || time(i) == f32::INFINITY),
                "a time neither finite nor +inf"
            );
        }
    } else {
        assert!(!(valid && required), "render refused {r:?}, layer {layer}, {} pixels: {status}", pixels.len);
        assert!(pixels.untouched(), "a failing render wrote");
    }
    Ok(())
}

fn run(u: &mut Unstructured) -> Result<()> {
    let p = glass_params(u)?;
    let made = create(u, &p, hibi_glass_memory_size, hibi_glass_memory_align, hibi_glass_create, hibi_glass_create_in)?;
    let Some((glass, memory)) = made else { return Ok(()) };
    let mut plate = Plate { glass, width: p.width, height: p.height, steps: 16, finished: false };
    let result = (|| {
        for _ in 0..12 {
            match u.int_in_range(0u8..=6)? {
                0 => impact(u, &mut plate)?,
                1..=3 => step(u, &mut plate)?,
                4 => crack(u, &plate)?,
                5 => fragments(u, &plate)?,
                _ => render(u, &plate)?,
            }
        }
        Ok(())
    })();
    if memory.is_empty() || u.arbitrary().unwrap_or(true) {
        // SAFETY: a live plate, not used afterwards.
        unsafe { hibi_glass_destroy(glass) };
    }
    drop(memory);
    result
}

fuzz_target!(|data: &[u8]| {
    let _ = run(&mut Unstructured::new(data));
});
