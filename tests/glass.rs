//! Model B against the paper's facts (Agui et al.) and hibi's own acceptance criteria.

use hibi_core::glass::{
    Crack, CrackEnd, CrackKind, CrackPoint, CrackSlot, Edge, FragmentBuild, Glass, GlassBuffers, GlassError,
    GlassLayers, GlassParams, GlassRender, STEP_PIECE, Vertex,
};
use hibi_core::polygon::Ring;
use hibi_tests::fnv1a64;

/// Runs `params` to the end of generation and hands the plate to `inspect`.
fn with_plate<R>(params: &GlassParams, inspect: impl FnOnce(&mut Glass) -> R) -> R {
    let m = params.memory().expect("valid parameters");
    let mut memory = m.allocate();
    let buffers = memory.buffers();
    let mut glass = Glass::new(params, buffers).expect("memory suffices");
    while !glass.step(100_000).finished {}
    inspect(&mut glass)
}

fn points(glass: &Glass, i: usize) -> Vec<CrackPoint> {
    let mut out = Vec::new();
    glass.for_each_point(i, |p| out.push(p));
    out
}

#[test]
fn radial_counts_are_poisson_and_large_and_ring_counts_follow_their_formulas() {
    let p = GlassParams::default();
    let mut ms = Vec::new();
    for seed in 0..200 {
        let counts = with_plate(&GlassParams { seed, ..p }, |g| g.impact_counts());
        let m = counts.radial as f32;
        assert_eq!(counts.large, (0.0606 * m + 3.293).floor() as u32, "N = ⌊eM + f⌋, seed {seed}");
        let rings = if m > 70.0 { (0.05 * m + 0.5).floor() as u32 } else { 0 };
        assert_eq!(counts.rings, rings, "R = ⌊aM + b⌋, seed {seed}");
        ms.push(f64::from(counts.radial));
    }
    let n = ms.len() as f64;
    let mean = ms.iter().sum::<f64>() / n;
    let variance = ms.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (n - 1.0);
    // Poisson(100): mean 100 (standard error 0.71), variance 100 (standard error ≈ 10).
    println!("M over 200 seeds: mean {mean:.2}, variance {variance:.1}");
    assert!((mean - 100.0).abs() < 4.0 * (100.0f64 / n).sqrt(), "mean {mean}");
    assert!((variance - 100.0).abs() < 4.0 * ((100.0 + 2.0 * 100.0 * 100.0) / n).sqrt(), "variance {variance}");
}

#[test]
fn every_crack_ends_exactly_on_the_edge_or_on_another_crack_and_large_ones_reach_the_edge() {
    for seed in 0..30 {
        let p = GlassParams { seed, ..GlassParams::default() };
        with_plate(&p, |g| {
            let all: Vec<Vec<CrackPoint>> = (0..g.crack_count()).map(|i| points(g, i)).collect();
            for (i, pts) in all.iter().enumerate() {
                let c = g.crack(i).unwrap();
                assert!(!c.growing, "seed {seed}: crack {i} still grows after generation ended");
                let Some(last) = pts.last() else { continue };
                let [x, y] = last.at;
                match c.end {
                    CrackEnd::Edge => assert!(
                        x == 0.0 || y == 0.0 || x == p.width || y == p.height,
                        "seed {seed}: crack {i} ends at {:?}, not on the edge",
                        last.at
                    ),
                    CrackEnd::Crack => {
                        // The meeting point is a vertex of the other crack too: no gap, no overshoot.
                        let shared =
                            all.iter().enumerate().any(|(j, other)| j != i && other.iter().any(|q| q.at == last.at));
                        assert!(shared, "seed {seed}: crack {i} ends at {:?}, not on another crack", last.at);
                    }
                    // Checked by `enclosed_cracks_stop_inside_regions_bounded_by_cracks_alone`.
                    CrackEnd::Generation | CrackEnd::Enclosed => {}
                    CrackEnd::Growing => unreachable!(),
                }
                if c.kind == CrackKind::Large {
                    assert_eq!(c.end, CrackEnd::Edge, "seed {seed}: large crack {i} stopped at {:?}", last.at);
                }
                // Times increase along every crack.
                assert!(pts.windows(2).all(|w| w[1].time >= w[0].time), "seed {seed}: crack {i}");
            }
        });
    }
}

#[test]
fn running_out_of_capacity_is_reported_not_a_panic() {
    let p = GlassParams { max_vertices: 64, ..GlassParams::default() };
    let progress = with_plate(&p, |g| g.progress());
    assert!(progress.capacity_reached && progress.finished && progress.vertices <= 64, "{progress:?}");
    let p = GlassParams { max_cracks: 10, ..GlassParams::default() };
    assert!(with_plate(&p, |g| g.progress()).capacity_reached);
}

/// A plate that ran out of capacity (down to two vertices: the impact point and one more)
/// stays usable: its fragments cover the plate after every step, whatever the budgets, and
/// the ring loop of an impact stops at the capacities.
#[test]
fn a_plate_out_of_capacity_stays_usable_down_to_two_vertices() {
    let fragments = |g: &mut Glass| {
        let (rings, points) = g.fragment_counts(&mut scratch(g)).unwrap();
        let (mut ring_out, mut point_out) = (vec![Ring::default(); rings], vec![[0.0f32; 2]; points]);
        assert_eq!(g.fragments(&mut scratch(g), &mut ring_out, &mut point_out), Ok((rings, points)));
        ring_out.iter().map(|r| r.area).sum::<f64>()
    };
    for (max_vertices, max_cracks, seed) in (0..6).flat_map(|s| [(2, 512, s), (3, 2, s), (5, 1, s), (40, 7, s)]) {
        let p = GlassParams { max_vertices, max_cracks, seed, ..GlassParams::default() };
        for budget in [1, 1000] {
            let m = p.memory().expect("valid parameters");
            let mut memory = m.allocate();
            let mut g = Glass::new(&p, memory.buffers()).expect("memory suffices");
            loop {
                let progress = g.step(budget);
                let area = fragments(&mut g);
                assert!((area - 640.0 * 640.0).abs() < 1e-3, "{p:?}, budget {budget}: area {area}");
                if progress.finished {
                    assert!(progress.capacity_reached && progress.vertices <= max_vertices, "{progress:?}");
                    break;
                }
            }
        }
    }
}

#[test]
fn a_second_impact_grows_cracks_that_stop_at_the_first() {
    let p = GlassParams::default();
    with_plate(&p, |g| {
        let first = g.crack_count();
        assert_eq!(g.impact([-1.0, 10.0]), Err(GlassError::Impact));
        g.impact([160.0, 480.0]).unwrap();
        while !g.step(100_000).finished {}
        let ends: Vec<CrackEnd> = (first..g.crack_count()).map(|i| g.crack(i).unwrap().end).collect();
        assert!(ends.contains(&CrackEnd::Crack), "no crack of the second impact met the first's");
        assert!(g.crack(0).unwrap().impact == 0 && g.crack(first).unwrap().impact == 1);
    });
}

/// Everything a caller can read of a plate, without stepping it: each crack (its record and
/// points), the progress (work left out: `step` adds to it), the counts of the latest impact,
/// a 64 × 64 mask and time raster, and the fragments.
fn readout(g: &Glass) -> String {
    let cracks: Vec<(Crack, Vec<CrackPoint>)> =
        (0..g.crack_count()).map(|i| (g.crack(i).unwrap(), points(g, i))).collect();
    let render = GlassRender { width: 64, height: 64, ..GlassRender::default() };
    let (mut mask, mut time) = (vec![0u8; 64 * 64], vec![0f32; 64 * 64]);
    g.render(&render, GlassLayers { mask: Some(&mut mask), time: Some(&mut time), ..Default::default() }).unwrap();
    let progress = hibi_core::glass::GlassProgress { work: 0, ..g.progress() };
    let time: Vec<u32> = time.iter().map(|t| t.to_bits()).collect();
    format!("{cracks:?} {progress:?} {:?} {mask:?} {time:?} {:?}", g.impact_counts(), fragments_of(g))
}

/// Creation's work does not grow with the capacities: `Glass::new` writes the first impact's
/// cracks and vertices (and their words) and nothing else, as many elements at `max_vertices`
/// 10⁴ as at 10⁶, and at `max_cracks` 512 as at 65 536, over buffers that hold a pattern (the
/// grids are emptied by `step`'s first units, an edge's stamp and a vertex's mark set when it
/// is added). The plate grown from those buffers is the one grown from zeroed buffers.
#[test]
fn creating_a_plate_writes_the_same_whatever_the_capacities() {
    let base = GlassParams { seed: 7, ..GlassParams::default() };
    let pattern = |i: usize| (i as u32).wrapping_mul(2_654_435_761) % 1000 + 1;
    let mut vertex = Vertex::default();
    vertex.at = [-1.0, -1.0];
    // A slot another plate wrote (its first crack, grown and stopped): none that creation writes.
    let crack = {
        let p = GlassParams { seed: 8, ..base };
        let m = p.memory().unwrap();
        let (mut cracks, mut vertices) = (vec![CrackSlot::default(); m.cracks], vec![Vertex::default(); m.vertices]);
        let (mut edges, mut words) = (vec![Edge::default(); m.edges], vec![0; m.words]);
        let buffers =
            GlassBuffers { cracks: &mut cracks, vertices: &mut vertices, edges: &mut edges, words: &mut words };
        let mut glass = Glass::new(&p, buffers).unwrap();
        while !glass.step(100_000).finished {}
        assert_ne!(cracks[0], CrackSlot::default());
        cracks[0]
    };
    // The elements `Glass::new` changed, and the plate those buffers grow.
    let created = |p: &GlassParams| {
        let m = p.memory().unwrap();
        let (mut cracks, mut vertices) = (vec![crack; m.cracks], vec![vertex; m.vertices]);
        let (mut edges, mut words) = (vec![Edge::default(); m.edges], (0..m.words).map(pattern).collect::<Vec<_>>());
        let buffers =
            GlassBuffers { cracks: &mut cracks, vertices: &mut vertices, edges: &mut edges, words: &mut words };
        let made = Glass::new(p, buffers).unwrap().progress();
        let changed = (
            cracks.iter().filter(|&&c| c != crack).count(),
            vertices.iter().filter(|&&v| v != vertex).count(),
            edges.iter().filter(|&&e| e != Edge::default()).count(),
            words.iter().enumerate().filter(|&(i, &w)| w != pattern(i)).count(),
        );
        let buffers =
            GlassBuffers { cracks: &mut cracks, vertices: &mut vertices, edges: &mut edges, words: &mut words };
        let mut glass = Glass::new(p, buffers).unwrap();
        while !glass.step(100_000).finished {}
        (made, changed, readout(&glass))
    };
    let (made, changed, plate) = created(&base);
    println!("creation of the default plate: {made:?}; changed (cracks, vertices, edges, words) {changed:?}");
    assert_eq!(changed.0, made.cracks as usize);
    assert_eq!(changed.1, made.vertices as usize);
    assert!(changed.2 == 0 && changed.3 <= 2 * made.vertices as usize, "{changed:?}");
    assert_eq!(plate, with_plate(&base, |g| readout(g)), "the plate grown over the pattern");
    for (max_vertices, max_cracks) in [(10_000, 512), (1_000_000, 512), (16_384, 65_536)] {
        let p = GlassParams { max_vertices, max_cracks, ..base };
        let (m, c, _) = created(&p);
        assert_eq!((m, c), (made, changed), "max_vertices {max_vertices}, max_cracks {max_cracks}");
    }
}

/// The environment variable that makes
/// [`creating_a_plate_takes_the_same_instructions_whatever_max_vertices`], run under Callgrind
/// by itself, create one case (its `max_vertices`) instead of measuring them all.
const CREATE_CASE: &str = "HIBI_GLASS_CREATE_CASE";

/// Creates a plate; the only function Callgrind counts in
/// [`creating_a_plate_takes_the_same_instructions_whatever_max_vertices`] (found by its
/// unmangled name).
#[unsafe(no_mangle)]
#[inline(never)]
fn hibi_test_glass_new<'a>(p: &GlassParams, buffers: GlassBuffers<'a>) -> Glass<'a> {
    Glass::new(p, buffers).expect("memory suffices")
}

/// What `Glass::new` costs, in instructions (Callgrind, so the same on any machine), does not
/// grow with the capacities: the default plate at `max_vertices` 10⁷ takes at most 1.1 times
/// the instructions of the one at 10⁵ (clearing every vertex's stamp and mark would take about
/// 80 times as many). Each case is created under Callgrind by this test binary itself (the
/// case named by [`CREATE_CASE`]), counting `hibi_test_glass_new` alone.
#[test]
fn creating_a_plate_takes_the_same_instructions_whatever_max_vertices() {
    const CASES: [u32; 2] = [100_000, 10_000_000];
    if let Ok(case) = std::env::var(CREATE_CASE) {
        // Under Callgrind: create the case and report what it holds.
        let p = GlassParams { max_vertices: case.parse().expect("a max_vertices"), ..GlassParams::default() };
        let mut memory = p.memory().expect("valid parameters").allocate();
        let glass = hibi_test_glass_new(&p, memory.buffers());
        println!("\nglass created {:?}", glass.progress());
        return;
    }
    let mut counts = Vec::new();
    for max_vertices in CASES {
        let (stdout, instructions) = hibi_tests::callgrind_this_test(
            "creating_a_plate_takes_the_same_instructions_whatever_max_vertices",
            "hibi_test_glass_new",
            (CREATE_CASE, &max_vertices.to_string()),
        );
        let what = format!("max_vertices {max_vertices}");
        let created = stdout.lines().find_map(|l| l.strip_prefix("glass created ")).map(str::to_owned);
        let created = created.unwrap_or_else(|| panic!("{what}: no plate reported in\n{stdout}"));
        // (Collection was on: drawing the first impact alone takes tens of thousands.)
        assert!(instructions > 10_000, "{what}: {instructions} instructions");
        println!("{what}: {instructions} instructions; {created}");
        counts.push((instructions, created));
    }
    assert_eq!(counts[0].1, counts[1].1, "the same plate");
    let (small, large) = (counts[0].0 as f64, counts[1].0 as f64);
    assert!(large <= 1.1 * small, "{large} instructions at max_vertices 10⁷, {small} at 10⁵");
}

/// The largest grids (a 4096-px plate: 256 × 256 cells each) are emptied by the first 2048
/// units of `step`, 64 cells a unit, within the budgets: no call does more than
/// max(budget, 1) − 1 + `STEP_PIECE` units. Until then every query reads the plate as it was
/// created, and an impact may be made; the plate grown does not depend on when it was made
/// or on the budgets.
#[test]
fn a_new_plate_empties_its_grids_within_the_step_budgets() {
    let p = GlassParams { width: 4096.0, height: 4096.0, impact: [2048.0, 2048.0], seed: 3, ..GlassParams::default() };
    let m = p.memory().unwrap();
    for budget in [0, 1, 7, 100] {
        let mut memory = m.allocate();
        let mut g = Glass::new(&p, memory.buffers()).unwrap();
        let created = readout(&g);
        while g.progress().work < 2048 {
            let before = g.progress().work;
            let progress = g.step(budget);
            let did = progress.work - before;
            assert!(did <= budget.max(1) - 1 + STEP_PIECE, "step({budget}) did {did} units");
            if progress.work <= 2048 {
                // Nothing but the grids' cells yet.
                assert_eq!(readout(&g), created, "budget {budget}, {} units", progress.work);
            }
        }
        assert_eq!(g.progress().time, 0);
    }
    // An impact while the grids are emptied: the plate is the one of an impact made at once.
    let second = [1000.0, 3000.0];
    let at_once = {
        let mut memory = m.allocate();
        let mut g = Glass::new(&p, memory.buffers()).unwrap();
        g.impact(second).unwrap();
        while !g.step(u64::MAX).finished {}
        readout(&g)
    };
    let mut memory = m.allocate();
    let mut g = Glass::new(&p, memory.buffers()).unwrap();
    while g.progress().work < 1000 {
        g.step(7);
    }
    g.impact(second).unwrap();
    assert!(g.progress().work < 2048 && !g.progress().finished);
    while !g.step(7).finished {}
    assert_eq!(readout(&g), at_once, "an impact made while the grids were emptied");
}

/// The golden plate (the paper's, seed 7) is the same, bit for bit, for budgets 1, 7 and
/// unbounded, its work included.
#[test]
fn the_golden_plate_does_not_depend_on_the_budgets() {
    let p = GlassParams { seed: 7, ..GlassParams::default() };
    let run = |budget: u64| {
        let m = p.memory().unwrap();
        let mut memory = m.allocate();
        let mut g = Glass::new(&p, memory.buffers()).unwrap();
        while !g.step(budget).finished {}
        (readout(&g), g.progress().work)
    };
    let unbounded = run(u64::MAX);
    assert_eq!(run(1), unbounded, "budget 1");
    assert_eq!(run(7), unbounded, "budget 7");
}

/// Once a capacity has run out generation has stopped for good, as every later step reports:
/// an impact is refused (`GlassError::Capacity`) and changes nothing. An impact that runs out
/// as it starts its cracks (a ring count past `max_cracks`) is made, and stops the plate at once.
#[test]
fn an_impact_after_a_capacity_stop_is_refused_and_changes_nothing() {
    let p = GlassParams { max_vertices: 400, seed: 5, ..GlassParams::default() };
    with_plate(&p, |g| {
        assert!(g.progress().capacity_reached);
        let before = readout(g);
        assert_eq!(g.impact([100.0, 100.0]), Err(GlassError::Capacity));
        assert_eq!(g.impact([-1.0, 100.0]), Err(GlassError::Impact));
        assert_eq!(readout(g), before);
        assert!(g.step(1000).capacity_reached);
        assert_eq!(readout(g), before);
    });
    let p = GlassParams { seed: 5, ..GlassParams::default() };
    with_plate(&p, |g| {
        let counts = g.impact([100.0, 100.0]).unwrap();
        assert!(!g.progress().capacity_reached && counts.radial > 0, "{counts:?}");
    });
    let p = GlassParams { ring_slope: 1e4, seed: 5, ..GlassParams::default() };
    let m = p.memory().unwrap();
    let mut memory = m.allocate();
    let mut g = Glass::new(&p, memory.buffers()).unwrap();
    let progress = g.progress();
    assert!(progress.capacity_reached && progress.finished, "{progress:?}");
    assert_eq!(g.impact([100.0, 100.0]), Err(GlassError::Capacity));
}

#[test]
fn bad_input_is_refused_before_anything_is_written() {
    let p = GlassParams { impact: [640.0, 10.0], ..GlassParams::default() };
    assert!(p.memory().is_err());
    let good = GlassParams::default();
    let m = good.memory().unwrap();
    let (mut cracks, mut vertices) = (vec![Default::default(); m.cracks], vec![Default::default(); m.vertices]);
    let (mut edges, mut words) = (vec![Default::default(); m.edges], vec![7u32; m.words - 1]);
    let buffers = GlassBuffers { cracks: &mut cracks, vertices: &mut vertices, edges: &mut edges, words: &mut words };
    assert_eq!(Glass::new(&good, buffers).err(), Some(GlassError::BufferTooSmall { needed: m.words }));
    assert!(words.iter().all(|&w| w == 7));
}

/// The golden scene: the paper's plate, seed 7.
#[test]
fn golden_cracks() {
    let p = GlassParams { seed: 7, ..GlassParams::default() };
    let hash = with_plate(&p, |g| {
        let mut bytes = Vec::new();
        for i in 0..g.crack_count() {
            bytes.extend((g.crack(i).unwrap().end as u32).to_le_bytes());
            g.for_each_point(i, |q| {
                for v in [q.at[0], q.at[1], q.time] {
                    bytes.extend(v.to_bits().to_le_bytes());
                }
            });
        }
        fnv1a64(&bytes)
    });
    assert_eq!(hash, 12276133656952694427, "the glass scene changed");
}

#[test]
fn rasters_draw_the_network_and_date_its_pixels() {
    use hibi_core::glass::{GlassLayers, GlassRender};
    use hibi_core::raster::RasterError;
    let p = GlassParams { seed: 3, ..GlassParams::default() };
    with_plate(&p, |g| {
        let render = GlassRender { width: 320, height: 320, ..GlassRender::default() };
        let (mut mask, mut time) = (vec![0u8; 320 * 320], vec![0.0f32; 320 * 320]);
        g.render(&render, GlassLayers { mask: Some(&mut mask), ..Default::default() }).unwrap();
        g.render(&render, GlassLayers { time: Some(&mut time), ..Default::default() }).unwrap();
        let cracked = mask.iter().filter(|&&v| v >= 128).count();
        assert!(cracked > 1000, "{cracked} cracked pixels");
        let last = g.progress().time as f32 + 1.0;
        for i in 0..mask.len() {
            if mask[i] >= 160 {
                assert!(time[i].is_finite() && (0.0..=last).contains(&time[i]), "pixel {i}: {}", time[i]);
            }
            if mask[i] == 0 {
                assert!(time[i].is_infinite(), "pixel {i}");
            }
        }
        // The impact point cracks first, the plate's edge last.
        assert!(time[160 * 320 + 160] < 1.0);
        let mut untouched = vec![9u8; 320 * 320 - 1];
        assert_eq!(
            g.render(&render, GlassLayers { mask: Some(&mut untouched), ..Default::default() }),
            Err(RasterError::BufferTooSmall { layer: hibi_core::raster::Layer::Mask, needed: 320 * 320 })
        );
        assert!(untouched.iter().all(|&v| v == 9));
        let thin = GlassRender { line_width: 0.0, ..render };
        assert_eq!(
            g.render(&thin, GlassLayers { mask: Some(&mut mask), ..Default::default() }),
            Err(RasterError::LineWidth)
        );
    });
}

/// Scratch for a fragment query on `g`.
fn scratch(g: &Glass) -> Vec<u32> {
    vec![0; g.params().memory().expect("valid").scratch]
}

/// The fragments of a plate: ring records and each ring's points.
fn fragments(g: &mut Glass) -> Vec<(Ring, Vec<[f32; 2]>)> {
    fragments_of(g)
}

/// [`fragments`] through a shared reference.
fn fragments_of(g: &Glass) -> Vec<(Ring, Vec<[f32; 2]>)> {
    let (rings, points) = g.fragment_counts(&mut scratch(g)).unwrap();
    let mut out = (vec![Ring::default(); rings], vec![[0.0f32; 2]; points]);
    assert_eq!(g.fragments(&mut scratch(g), &mut out.0, &mut out.1), Ok((rings, points)));
    out.0.iter().map(|r| (*r, out.1[r.first_point as usize..][..r.point_count as usize].to_vec())).collect()
}

/// Whether `p` is inside `ring` (even–odd rule; `p` must not lie on it).
fn ring_contains(ring: &[[f32; 2]], p: [f64; 2]) -> bool {
    let mut inside = false;
    for (a, b) in ring.iter().zip(ring.iter().cycle().skip(1)) {
        let (ax, ay, bx, by) = (a[0] as f64, a[1] as f64, b[0] as f64, b[1] as f64);
        if (ay > p[1]) != (by > p[1]) && p[0] < ax + (p[1] - ay) * (bx - ax) / (by - ay) {
            inside = !inside;
        }
    }
    inside
}

/// Checks that the fragments tile the plate: signed areas add up to W·H, and sample points
/// lie in exactly one fragment (in its outer ring and in none of its holes).
fn assert_fragments_tile(p: &GlassParams, frags: &[(Ring, Vec<[f32; 2]>)], what: &str) {
    let plate = f64::from(p.width) * f64::from(p.height);
    let total: f64 = frags.iter().map(|(r, _)| r.area).sum();
    assert!((total - plate).abs() < 1e-6 * plate, "{what}: areas add up to {total}, not {plate}");
    for (i, (r, ring)) in frags.iter().enumerate() {
        let shoelace: f64 = ring
            .iter()
            .zip(ring.iter().cycle().skip(1))
            .map(|(a, b)| 0.5 * (a[0] as f64 * b[1] as f64 - b[0] as f64 * a[1] as f64))
            .sum();
        assert!((shoelace - r.area).abs() < 1e-6 * plate, "{what}: ring {i} area {} vs its points {shoelace}", r.area);
        assert_eq!(r.hole_of == u32::MAX, r.area > 0.0, "{what}: ring {i} is a hole exactly when it is clockwise");
        assert!(ring.iter().all(|q| (0.0..=p.width).contains(&q[0]) && (0.0..=p.height).contains(&q[1])));
    }
    // A deterministic cloud of sample points (irrational steps, so none lands on a crack).
    for k in 0..4000 {
        let q = [
            (k as f64 * 0.618_033_988_75).fract() * f64::from(p.width),
            (k as f64 * 0.414_213_562_37 + 0.1).fract() * f64::from(p.height),
        ];
        let count: i32 = frags
            .iter()
            .filter(|(_, ring)| ring_contains(ring, q))
            .map(|(r, _)| if r.area > 0.0 { 1 } else { -1 })
            .sum();
        assert_eq!(count, 1, "{what}: point {q:?} lies in {count} fragments");
    }
}

#[test]
fn fragments_cover_the_plate_exactly_once() {
    let mut rings = 0;
    for seed in 0..12 {
        let p = GlassParams { seed, ..GlassParams::default() };
        with_plate(&p, |g| {
            let frags = fragments(g);
            rings += frags.len();
            assert!(frags.len() > 20, "seed {seed}: only {} fragments", frags.len());
            assert_fragments_tile(&p, &frags, &format!("seed {seed}"));
            // Every large crack reaches the edge, so the fragments around the impact reach it too.
            assert!(frags.iter().any(|(_, ring)| ring.iter().any(|q| q[0] == 0.0)));
        });
    }
    println!("12 plates: {rings} fragment rings");
}

#[test]
fn fragments_of_several_impacts_and_of_a_cut_short_run_still_tile_the_plate() {
    let p = GlassParams { seed: 5, ..GlassParams::default() };
    with_plate(&p, |g| {
        for at in [[150.0, 450.0], [500.0, 120.0]] {
            g.impact(at).unwrap();
            while !g.step(100_000).finished {}
        }
        assert_fragments_tile(&p, &fragments(g), "three impacts");
    });
    // Capacity runs out before the large cracks reach the edge: dead ends are pruned, the
    // closed loops left are fragments, and whatever they do not cover is the plate's own.
    let p = GlassParams { seed: 5, max_vertices: 400, ..GlassParams::default() };
    with_plate(&p, |g| {
        assert!(g.progress().capacity_reached);
        let frags = fragments(g);
        // Here the network around the impact is an island: its outside is a hole in the plate.
        let holes: Vec<_> = frags.iter().filter(|(r, _)| r.area < 0.0).collect();
        assert!(!holes.is_empty() && holes.iter().all(|(r, _)| frags[r.hole_of as usize].0.area > 0.0));
        assert_fragments_tile(&p, &frags, "capacity");
    });
    // Part way through growth.
    let p = GlassParams { seed: 6, ..GlassParams::default() };
    let m = p.memory().unwrap();
    let mut memory = m.allocate();
    let buffers = memory.buffers();
    let mut g = Glass::new(&p, buffers).unwrap();
    for _ in 0..4 {
        g.step(150);
        assert_fragments_tile(&p, &fragments(&mut g), "mid-growth");
    }
}

/// Whether `p` lies on the segment `a`–`z`, decided as the core decides it (f32 arithmetic).
fn on_segment(a: [f32; 2], z: [f32; 2], p: [f32; 2]) -> bool {
    let (d, q) = ([z[0] - a[0], z[1] - a[1]], [p[0] - a[0], p[1] - a[1]]);
    let along = q[0] * d[0] + q[1] * d[1];
    d[0] * q[1] - d[1] * q[0] == 0.0 && along > 0.0 && along < d[0] * d[0] + d[1] * d[1]
}

/// Twice the area of the convex pieces of `frags` (hibi_core::polygon), each polygon's
/// outer ring less its holes.
fn pieces_area(frags: &[(Ring, Vec<[f32; 2]>)]) -> f64 {
    use hibi_core::polygon::{ConvexPiece, convex_pieces, piece_counts, pieces_scratch};
    let mut points = Vec::new();
    let rings: Vec<Ring> = frags
        .iter()
        .map(|(r, ring)| {
            let first = points.len() as u32;
            points.extend_from_slice(ring);
            Ring { first_point: first, ..*r }
        })
        .collect();
    let mut scratch = vec![0u32; pieces_scratch(&rings, &points).unwrap()];
    let counts = piece_counts(&rings, &points, &mut scratch).unwrap();
    let mut pieces = vec![ConvexPiece::default(); counts.pieces];
    convex_pieces(&rings, &points, &mut scratch, &mut pieces).unwrap();
    let mut twice = 0.0f64;
    for piece in &pieces {
        let n = piece.point_count as usize;
        for k in 0..n {
            let [a, b] = [piece.points[k], piece.points[(k + 1) % n]].map(|i| points[i as usize].map(f64::from));
            twice += a[0] * b[1] - b[0] * a[1];
        }
    }
    twice
}

/// An impact on an earlier crack starts from it: at the first impact's own point, at a
/// vertex of one of its cracks, or inside one of its segments, the new cracks share the
/// point's vertex (or split the segment there), the fragments still tile the plate and each
/// ring stays simple, so that their convex pieces add up to the plate too. (A second hub at
/// the first one's point, unjoined, let the two impacts' cracks cross each other: a fragment
/// ring crossed itself and its pieces covered 1.1 times a small plate.)
#[test]
fn an_impact_on_an_earlier_crack_starts_from_it() {
    let p = GlassParams { seed: 3, ..GlassParams::default() };
    let plate = f64::from(p.width) * f64::from(p.height);
    let first = with_plate(&p, |g| points(g, 0));
    let vertex = first[first.len() / 2].at;
    let on_segment_point = first
        .windows(2)
        .flat_map(|w| (1..64).map(move |k| (w[0].at, w[1].at, k as f32 / 64.0)))
        .map(|(a, z, t)| (a, z, [a[0] + t * (z[0] - a[0]), a[1] + t * (z[1] - a[1])]))
        .find(|&(a, z, q)| on_segment(a, z, q) && q != a && q != z)
        .map(|(_, _, q)| q)
        .expect("a point exactly on a segment of the first crack");
    for (what, at) in [("the impact's point", p.impact), ("a crack's vertex", vertex), ("a segment", on_segment_point)]
    {
        with_plate(&p, |g| {
            g.impact(at).unwrap();
            while !g.step(100_000).finished {}
            let frags = fragments(g);
            assert_fragments_tile(&p, &frags, what);
            let pieces = 0.5 * pieces_area(&frags);
            assert!((pieces - plate).abs() < 1e-4 * plate, "{what}: pieces cover {pieces} of a {plate} plate");
        });
    }
}

/// Fragment queries only read the plate: four threads query one plate at once, each with
/// its own scratch, and get what one query alone gets. A short scratch is refused, naming the
/// words it needs.
#[test]
fn fragment_queries_share_the_plate_across_threads() {
    with_plate(&GlassParams { seed: 4, ..GlassParams::default() }, |g| {
        let alone = fragments(g);
        let g = &*g;
        let together = hibi_tests::on_four_threads(|| fragments_of(g));
        assert!(together.iter().all(|f| *f == alone));
        let needed = g.params().memory().unwrap().scratch;
        let mut short = vec![0; needed - 1];
        assert_eq!(g.fragment_counts(&mut short), Err(GlassError::BufferTooSmall { needed }));
    });
}

#[test]
fn fragments_are_written_only_into_buffers_that_fit() {
    with_plate(&GlassParams { seed: 2, ..GlassParams::default() }, |g| {
        let (rings, points) = g.fragment_counts(&mut scratch(g)).unwrap();
        let mut short = (vec![Ring::default(); rings], vec![[9.0f32; 2]; points - 1]);
        assert_eq!(
            g.fragments(&mut scratch(g), &mut short.0, &mut short.1),
            Err(GlassError::BufferTooSmall { needed: points })
        );
        assert!(short.0.iter().all(|r| *r == Ring::default()) && short.1.iter().all(|q| *q == [9.0; 2]));
        let mut short = (vec![Ring::default(); rings - 1], vec![[9.0f32; 2]; points]);
        assert_eq!(
            g.fragments(&mut scratch(g), &mut short.0, &mut short.1),
            Err(GlassError::BufferTooSmall { needed: rings })
        );
        assert!(short.1.iter().all(|q| *q == [9.0; 2]));
        // Asking twice gives the same answer: the walk leaves no trace in the plate.
        assert_eq!(fragments(g), fragments(g));
    });
}

#[test]
fn enclosed_cracks_stop_inside_regions_bounded_by_cracks_alone() {
    let mut enclosed = 0;
    for seed in 0..12 {
        let p = GlassParams { seed, ..GlassParams::default() };
        with_plate(&p, |g| {
            let frags = fragments(g);
            for i in 0..g.crack_count() {
                if g.crack(i).unwrap().end != CrackEnd::Enclosed {
                    continue;
                }
                enclosed += 1;
                let tip = points(g, i).last().map_or(g.crack(i).unwrap().tip, |q| q.at);
                let q = [f64::from(tip[0]) + 1e-4, f64::from(tip[1]) + 1e-4];
                let home: Vec<_> = frags.iter().filter(|(r, ring)| r.area > 0.0 && ring_contains(ring, q)).collect();
                assert_eq!(home.len(), 1, "seed {seed}: crack {i}'s tip {tip:?}");
                let on_border = |v: &[f32; 2]| v[0] == 0.0 || v[1] == 0.0 || v[0] == p.width || v[1] == p.height;
                assert!(
                    !home[0].1.iter().any(on_border),
                    "seed {seed}: enclosed crack {i} stopped in a region that reaches the plate's edge"
                );
            }
        });
    }
    println!("12 plates: {enclosed} cracks stopped by stop condition 2");
    assert!(enclosed > 12, "the closed-region rule hardly fired: {enclosed}");
}

// ---------------------------------------------------------------------------------------
// The paper's geometry (its growth rules and figures), measured from the polylines as a user
// sees them.

/// One plate's cracks: kind, end, ring (centre, radius) and points.
struct Plate {
    impact: [f32; 2],
    counts: hibi_core::glass::ImpactCounts,
    cracks: Vec<(hibi_core::glass::Crack, Vec<[f32; 2]>)>,
}

fn plate(p: &GlassParams) -> Plate {
    with_plate(p, |g| Plate {
        impact: p.impact,
        counts: g.impact_counts(),
        cracks: (0..g.crack_count())
            .map(|i| (g.crack(i).unwrap(), points(g, i).iter().map(|q| q.at).collect()))
            .collect(),
    })
}

fn sub(a: [f32; 2], b: [f32; 2]) -> [f64; 2] {
    [f64::from(a[0]) - f64::from(b[0]), f64::from(a[1]) - f64::from(b[1])]
}

fn direction(a: [f64; 2]) -> f64 {
    a[1].atan2(a[0])
}

/// `a` wrapped into (−π, π].
fn wrapped(a: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let r = a - tau * (a / tau).floor();
    if r > std::f64::consts::PI { r - tau } else { r }
}

/// The angle between two lines in degrees, within [0, 90].
fn line_angle(a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = wrapped(direction(a) - direction(b)).abs().to_degrees();
    if d > 90.0 { 180.0 - d } else { d }
}

/// For every crack that stopped on another crack: the angle (degrees, 0–90) between its last
/// piece and the crack it met at the meeting point (that crack's line through the point: from
/// its vertex before to its vertex after when the point is inside it, else its piece there),
/// and the meeting point's distance from the impact.
fn meeting_angles(plate: &Plate) -> Vec<(f64, f64)> {
    // Where each crack vertex lies: (crack, index), by the point's bits.
    let mut at: std::collections::HashMap<[u32; 2], Vec<(usize, usize)>> = std::collections::HashMap::new();
    for (j, (_, pts)) in plate.cracks.iter().enumerate() {
        for (k, v) in pts.iter().enumerate() {
            at.entry([v[0].to_bits(), v[1].to_bits()]).or_default().push((j, k));
        }
    }
    let mut out = Vec::new();
    for (i, (c, pts)) in plate.cracks.iter().enumerate() {
        if c.end != CrackEnd::Crack || pts.len() < 2 {
            continue;
        }
        let q = pts[pts.len() - 1];
        let last = sub(q, pts[pts.len() - 2]);
        let mut met = None;
        for &(j, k) in at.get(&[q[0].to_bits(), q[1].to_bits()]).into_iter().flatten() {
            let other = &plate.cracks[j].1;
            if j == i || other.len() < 2 {
                continue;
            }
            let interior = k > 0 && k + 1 < other.len();
            let line = if interior {
                sub(other[k + 1], other[k - 1])
            } else if k > 0 {
                sub(other[k], other[k - 1])
            } else {
                sub(other[1], other[0])
            };
            if met.is_none() || interior {
                met = Some(line);
            }
            if interior {
                break;
            }
        }
        if let Some(line) = met {
            let r = sub(q, plate.impact);
            out.push((line_angle(last, line), (r[0] * r[0] + r[1] * r[1]).sqrt()));
        }
    }
    out
}

/// Per ring crack with at least two pieces: the largest relative distance of a vertex from
/// its radius d_i; its turning, signed in its own sense, from the direction it started in
/// (the tangent of its circle at its start point C_i) to its last piece's; and the arc it
/// spans, the angle at the impact from C_i to its last piece's midpoint. A crack following
/// its circle turns as much as the arc (a circle's tangent turns with the angle at its
/// centre); a chord does not turn at all.
fn ring_figures(plate: &Plate) -> Vec<(f64, f64, f64)> {
    let mut out = Vec::new();
    for (c, pts) in &plate.cracks {
        let sense = match c.kind {
            CrackKind::RingCounterClockwise => 1.0,
            CrackKind::RingClockwise => -1.0,
            _ => continue,
        };
        if pts.len() < 2 {
            continue;
        }
        let (centre, d) = (c.ring.0, f64::from(c.ring.1));
        let off = pts
            .iter()
            .map(|&v| {
                let r = sub(v, centre);
                ((r[0] * r[0] + r[1] * r[1]).sqrt() - d).abs() / d
            })
            .fold(0.0, f64::max);
        let start = direction(sub(pts[0], centre));
        let tangent = start + sense * std::f64::consts::FRAC_PI_2;
        let n = pts.len();
        let turning = wrapped(direction(sub(pts[n - 1], pts[n - 2])) - tangent);
        let mid = [(pts[n - 2][0] + pts[n - 1][0]) / 2.0, (pts[n - 2][1] + pts[n - 1][1]) / 2.0];
        let span = wrapped(direction(sub(mid, centre)) - start);
        out.push((off, sense * turning, sense * span));
    }
    out
}

/// The points of a polyline every `step` of its length from its start.
fn resample(pts: &[[f32; 2]], step: f64) -> Vec<[f64; 2]> {
    let mut out = Vec::new();
    let Some(&first) = pts.first() else { return out };
    out.push([f64::from(first[0]), f64::from(first[1])]);
    let mut next = step;
    let mut walked = 0.0;
    for w in pts.windows(2) {
        let d = sub(w[1], w[0]);
        let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
        while len > 0.0 && next <= walked + len {
            let t = (next - walked) / len;
            out.push([f64::from(w[0][0]) + d[0] * t, f64::from(w[0][1]) + d[1] * t]);
            next += step;
        }
        walked += len;
    }
    out
}

/// The turning angles (degrees) between successive 10-pixel pieces of every radial crack
/// (paper Fig. 5), each with the distance of its vertex from the impact.
fn radial_turns(plate: &Plate) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for (c, pts) in &plate.cracks {
        if !matches!(c.kind, CrackKind::Large | CrackKind::Radial) {
            continue;
        }
        let r = resample(pts, 10.0);
        for w in r.windows(3) {
            let a = [w[1][0] - w[0][0], w[1][1] - w[0][1]];
            let b = [w[2][0] - w[1][0], w[2][1] - w[1][1]];
            let at = [w[1][0] - f64::from(plate.impact[0]), w[1][1] - f64::from(plate.impact[1])];
            out.push((wrapped(direction(b) - direction(a)).to_degrees(), (at[0] * at[0] + at[1] * at[1]).sqrt()));
        }
    }
    out
}

fn percentile(sorted: &[f64], q: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

/// Least-squares line y = a·x + b through the points, and the correlation r.
fn fit(points: &[(f64, f64)]) -> (f64, f64, f64) {
    let n = points.len() as f64;
    let (mx, my) = (points.iter().map(|p| p.0).sum::<f64>() / n, points.iter().map(|p| p.1).sum::<f64>() / n);
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let syy: f64 = points.iter().map(|p| (p.1 - my).powi(2)).sum();
    let a = sxy / sxx;
    (a, my - a * mx, sxy / (sxx * syy).sqrt())
}

/// The geometry of 100 default plates (seeds 0–99), measured once for the tests below.
struct Geometry {
    /// Meeting angle and distance from the impact, per crack that stopped on a crack.
    meetings: Vec<(f64, f64)>,
    /// Per ring crack: largest relative distance from d_i, turning, arc (radians).
    rings: Vec<(f64, f64, f64)>,
    /// Turning angle between successive 10 px pieces of radial cracks, and its distance.
    turns: Vec<(f64, f64)>,
    /// Large cracks, and how many reached the edge.
    large: (usize, usize),
    /// Per crack that stopped on the plate's edge: the angle (degrees, 0–90) between its last
    /// piece and the edge.
    edge_meetings: Vec<f64>,
    /// How the other radial cracks ended: on the edge, on a crack, at the end of generation,
    /// enclosed (indexed by `CrackEnd`).
    radial_ends: [usize; 5],
}

const PLATES: u64 = 100;

fn geometry() -> &'static Geometry {
    static GEOMETRY: std::sync::OnceLock<Geometry> = std::sync::OnceLock::new();
    GEOMETRY.get_or_init(|| measure_geometry(GlassParams::default().radial_mean))
}

/// The geometry of [`PLATES`] default plates (seeds 0–99) with M_ave = `radial_mean`.
fn measure_geometry(radial_mean: f32) -> Geometry {
    {
        let mut g = Geometry {
            meetings: Vec::new(),
            rings: Vec::new(),
            turns: Vec::new(),
            large: (0, 0),
            edge_meetings: Vec::new(),
            radial_ends: [0; 5],
        };
        for seed in 0..PLATES {
            let p = GlassParams { seed, radial_mean, ..GlassParams::default() };
            let pl = plate(&p);
            g.meetings.extend(meeting_angles(&pl));
            g.rings.extend(ring_figures(&pl));
            g.turns.extend(radial_turns(&pl));
            for (c, _) in pl.cracks.iter().filter(|(c, _)| c.kind == CrackKind::Large) {
                g.large.0 += 1;
                g.large.1 += usize::from(c.end == CrackEnd::Edge);
            }
            for (_, pts) in pl.cracks.iter().filter(|(c, _)| c.end == CrackEnd::Edge) {
                let (q, before) = (pts[pts.len() - 1], pts[pts.len() - 2]);
                let edge = if q[0] == 0.0 || q[0] == p.width { [0.0, 1.0] } else { [1.0, 0.0] };
                g.edge_meetings.push(line_angle(sub(q, before), edge));
            }
            for (c, _) in pl.cracks.iter().filter(|(c, _)| c.kind == CrackKind::Radial) {
                g.radial_ends[c.end as usize] += 1;
            }
        }
        g
    }
}

fn sorted(values: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut v: Vec<f64> = values.collect();
    v.sort_by(f64::total_cmp);
    v
}

/// Rule 8: tips meet other cracks at right angles (F2 turns them, over updates cut short as
/// they close in). The hub is included: its short radial cracks run straight out (F3 scaled
/// by weight(t)) and end on a large crack, a neighbour or a ring crack (at the angles printed
/// per distance from the impact), in a region enclosed by cracks, or at the end of generation
/// (the counts are printed).
#[test]
fn tips_meet_cracks_at_right_angles() {
    let g = geometry();
    let all = sorted(g.meetings.iter().map(|m| m.0));
    let median = percentile(&all, 0.5);
    let square = all.iter().filter(|&&a| a >= 60.0).count() as f64 / all.len() as f64;
    println!(
        "{PLATES} plates: {} tips stopped on a crack; median meeting angle {median:.1} deg, {:.1} % within 60-90 deg",
        all.len(),
        100.0 * square
    );
    for (lo, hi) in [(0.0, 30.0), (30.0, 60.0), (60.0, 120.0), (120.0, f64::INFINITY)] {
        let part = sorted(g.meetings.iter().filter(|m| m.1 >= lo && m.1 < hi).map(|m| m.0));
        if !part.is_empty() {
            let square = part.iter().filter(|&&a| a >= 60.0).count() as f64 / part.len() as f64;
            println!(
                "  {lo}-{hi} px from the impact: {} meetings, median {:.1} deg, {:.1} % within 60-90",
                part.len(),
                percentile(&part, 0.5),
                100.0 * square
            );
        }
    }
    let e = g.radial_ends;
    println!(
        "  the {} short radial cracks end: {} on a crack, {} at the end of generation, {} enclosed, {} on the edge",
        e.iter().sum::<usize>(),
        e[CrackEnd::Crack as usize],
        e[CrackEnd::Generation as usize],
        e[CrackEnd::Enclosed as usize],
        e[CrackEnd::Edge as usize]
    );
    assert!(all.len() > 20 * PLATES as usize, "only {} meetings", all.len());
    assert!(median >= 60.0, "median meeting angle {median:.1} deg (rule 8: meetings near a right angle; at least 60)");
    assert!(square >= 0.5, "{:.1} % of meetings within 60-90 deg (rule 8: at least 50 %)", 100.0 * square);
}

/// Of the growing tips farther than 60 px from the impact at the end of each time step (seeds
/// 0–99), the share within 10 px of another growing tip.
fn close_tips(tip_repulsion: f32) -> (usize, f64) {
    let (mut close, mut total) = (0usize, 0usize);
    for seed in 0..PLATES {
        let p = GlassParams { seed, tip_repulsion, ..GlassParams::default() };
        with_plate_stepped(&p, |g| {
            let tips: Vec<[f32; 2]> =
                (0..g.crack_count()).filter_map(|i| g.crack(i)).filter(|c| c.growing).map(|c| c.tip).collect();
            for (i, &a) in tips.iter().enumerate() {
                let r = sub(a, p.impact);
                if (r[0] * r[0] + r[1] * r[1]).sqrt() < 60.0 {
                    continue;
                }
                total += 1;
                close += usize::from(tips.iter().enumerate().any(|(j, &b)| {
                    let d = sub(a, b);
                    j != i && d[0] * d[0] + d[1] * d[1] < 100.0
                }));
            }
        });
    }
    (total, close as f64 / total as f64)
}

/// Runs a plate to its end, calling `at_step` after every time step.
fn with_plate_stepped(p: &GlassParams, mut at_step: impl FnMut(&Glass)) {
    let m = p.memory().unwrap();
    let mut memory = m.allocate();
    let mut g = Glass::new(p, memory.buffers()).unwrap();
    let mut time = 0;
    loop {
        let progress = g.step(1);
        if progress.time != time || progress.finished {
            time = progress.time;
            at_step(&g);
        }
        if progress.finished {
            break;
        }
    }
}

/// Rule 7: growing tips move away from each other. F1 (from tips in S growing towards the
/// tip) leaves fewer tips close to another than no F1 does.
#[test]
fn tips_move_away_from_each_other() {
    let (samples, with) = close_tips(GlassParams::default().tip_repulsion);
    let (_, without) = close_tips(0.0);
    println!(
        "{PLATES} plates, {samples} tip positions beyond 60 px: {:.2} % within 10 px of another growing tip, {:.2} % without F1",
        100.0 * with,
        100.0 * without
    );
    assert!(with <= 0.95 * without, "F1 does not keep tips apart: {with:.4} against {without:.4} without it");
}

/// Rule 5: ring cracks grow along their circle of radius d_i: arcs, not chords.
#[test]
fn ring_cracks_follow_their_circle() {
    let g = geometry();
    let worst = g.rings.iter().map(|r| r.0).fold(0.0, f64::max);
    // Rounding of the f32 vertices: a crack that keeps exactly to its chords may measure a
    // hair under its arc.
    const ROUNDING: f64 = 1e-3;
    let short: Vec<_> = g.rings.iter().filter(|r| r.1 < r.2 - ROUNDING).collect();
    let (turning, arc) = g.rings.iter().fold((0.0, 0.0), |a, r| (a.0 + r.1, a.1 + r.2));
    let least = g.rings.iter().map(|r| (r.1 - r.2).to_degrees()).fold(f64::INFINITY, f64::min);
    println!(
        "{PLATES} plates: {} ring cracks; every vertex within {:.1} % of d_i; mean turning {:.1} deg over mean arc {:.1} deg; each turns at least its arc plus {least:.2} deg",
        g.rings.len(),
        100.0 * worst,
        turning.to_degrees() / g.rings.len() as f64,
        arc.to_degrees() / g.rings.len() as f64,
    );
    assert!(g.rings.len() > 5 * PLATES as usize);
    assert!(worst <= 0.1, "a ring crack's vertex strays {:.1} % from its radius", 100.0 * worst);
    // A chord turns 0 while its arc is 10-40 deg. Each ring crack turns at least as much as
    // the arc it spans: no update turns it outwards of the chord of its circle it spans.
    assert!(short.is_empty(), "{} of {} ring cracks turn less than their arc", short.len(), g.rings.len());
}

/// Rule 6 and Fig. 5: the turning between successive 10 px pieces of radial cracks is spread
/// like the paper's (about -22.5 to 27.5 deg) and symmetric about 0.
#[test]
fn radial_cracks_turn_like_the_papers_fig_5() {
    let g = geometry();
    let turns = sorted(g.turns.iter().map(|t| t.0));
    let (p1, p99) = (percentile(&turns, 0.01), percentile(&turns, 0.99));
    let mean = turns.iter().sum::<f64>() / turns.len() as f64;
    println!(
        "{PLATES} plates: {} turns; 1st percentile {p1:.1} deg, 99th {p99:.1} deg, mean {mean:.2} deg",
        turns.len()
    );
    assert!(p1 < -18.0 && p99 > 18.0, "1st/99th percentiles {p1:.1} / {p99:.1} deg (Fig. 5's spread: beyond -18 / 18)");
    assert!(mean.abs() <= 2.0, "mean turn {mean:.2} deg");
}

/// Rules 2, 3 and 8: large cracks reach the edge, and meet it at right angles; radial cracks
/// are nearly straight near the impact and bend further out.
#[test]
fn large_cracks_reach_the_edge_and_radial_cracks_are_straighter_near_the_impact() {
    let g = geometry();
    let (large, reached) = g.large;
    let edge = sorted(g.edge_meetings.iter().copied());
    let square = edge.iter().filter(|&&a| a >= 60.0).count() as f64 / edge.len() as f64;
    println!(
        "{PLATES} plates: {reached} of {large} large cracks reach the edge; {} cracks meet the edge at a median {:.1} deg, {:.1} % within 60-90 deg",
        edge.len(),
        percentile(&edge, 0.5),
        100.0 * square
    );
    assert!(reached * 100 >= large * 99, "{reached} of {large}");
    // Rule 8 at the plate's edge.
    assert!(percentile(&edge, 0.5) >= 60.0 && square >= 0.5, "edge meetings: median {:.1}", percentile(&edge, 0.5));
    let mean_turn = |lo: f64, hi: f64| {
        let t: Vec<f64> = g.turns.iter().filter(|t| t.1 >= lo && t.1 < hi).map(|t| t.0.abs()).collect();
        t.iter().sum::<f64>() / t.len() as f64
    };
    let (near, far) = (mean_turn(0.0, 60.0), mean_turn(120.0, f64::INFINITY));
    println!("  mean |turn| within 60 px of the impact {near:.2} deg, beyond 120 px {far:.2} deg");
    assert!(near < 0.75 * far, "near {near:.2}, far {far:.2}");
}

/// Table 1's fits over M = 40..200: N (radial cracks reaching the edge) against M, and the
/// mean ring radius d_ave against M, beside the paper's.
#[test]
fn table_1_fits_hold_over_m_40_to_200() {
    let (mut n_points, mut d_points) = (Vec::new(), Vec::new());
    for mean in (40..=200).step_by(20) {
        for seed in 0..8u64 {
            let p = GlassParams { radial_mean: mean as f32, seed: 1000 + seed, ..GlassParams::default() };
            let pl = plate(&p);
            let m = f64::from(pl.counts.radial);
            let reached = pl
                .cracks
                .iter()
                .filter(|(c, _)| matches!(c.kind, CrackKind::Large | CrackKind::Radial) && c.end == CrackEnd::Edge)
                .count();
            n_points.push((m, reached as f64));
            let radii: Vec<f64> = pl
                .cracks
                .iter()
                .filter(|(c, _)| matches!(c.kind, CrackKind::RingClockwise | CrackKind::RingCounterClockwise))
                .flat_map(|(_, pts)| {
                    pts.iter().map(|&v| {
                        let r = sub(v, pl.impact);
                        (r[0] * r[0] + r[1] * r[1]).sqrt()
                    })
                })
                .collect();
            if !radii.is_empty() {
                d_points.push((m, radii.iter().sum::<f64>() / radii.len() as f64));
            }
        }
    }
    let (ne, nf, nr) = fit(&n_points);
    let (dg, dh, dr) = fit(&d_points);
    println!("N = {ne:.4} M + {nf:.3} (r = {nr:.3}); paper: N = 0.0606 M + 3.293 (r = 0.936)");
    println!("d_ave = {dg:.3} M + {dh:.2} px (r = {dr:.3}); paper: d_ave = 0.470 M + 13.90 (r = 0.994)");
    // The fitted lines within 10 % of the paper's over the range.
    for m in [40.0, 200.0] {
        let (ours, paper) = (ne * m + nf, 0.0606 * m + 3.293);
        assert!((ours - paper).abs() <= 0.1 * paper, "N at M = {m}: {ours:.2} against {paper:.2}");
    }
    for m in [80.0, 200.0] {
        let (ours, paper) = (dg * m + dh, 0.470 * m + 13.90);
        assert!((ours - paper).abs() <= 0.1 * paper, "d_ave at M = {m}: {ours:.2} against {paper:.2}");
    }
    assert!(nr > 0.9 && dr > 0.9, "correlations {nr:.3} {dr:.3}");
}

/// The figures of the geometry tests above (rules 5, 6, 8 and Fig. 5) at M_ave = 40, 100 and
/// 200, 100 plates each (seeds 0–99), one line per M_ave; the Table 1 fits come from
/// `table_1_fits_hold_over_m_40_to_200`. Crowding costs geometry at 200 (neighbouring radial
/// cracks are closer); the tests above hold the default's figures.
///
///     cargo test --release --test glass geometry_at_m_40_100_200 -- --ignored --nocapture
#[test]
#[ignore = "prints figures: 300 plates"]
fn geometry_at_m_40_100_200() {
    println!(
        "| M_ave | meetings | median meeting | within 60-90 | edge median | ring cracks | worst ring vertex | rings short of their arc | turn p1 / p99 / mean | large reaching the edge |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for mean in [40.0f32, 100.0, 200.0] {
        let g = measure_geometry(mean);
        let all = sorted(g.meetings.iter().map(|m| m.0));
        let square = all.iter().filter(|&&a| a >= 60.0).count() as f64 / all.len() as f64;
        let edge = sorted(g.edge_meetings.iter().copied());
        let worst = g.rings.iter().map(|r| r.0).fold(0.0, f64::max);
        let short = g.rings.iter().filter(|r| r.1 < r.2 - 1e-3).count();
        let turns = sorted(g.turns.iter().map(|t| t.0));
        let turn_mean = turns.iter().sum::<f64>() / turns.len() as f64;
        println!(
            "| {mean} | {} | {:.1}° | {:.1} % | {:.1}° | {} | {:.1} % | {short} | {:.1}° / {:.1}° / {turn_mean:.2}° | {} of {} |",
            all.len(),
            percentile(&all, 0.5),
            100.0 * square,
            percentile(&edge, 0.5),
            g.rings.len(),
            100.0 * worst,
            percentile(&turns, 0.01),
            percentile(&turns, 0.99),
            g.large.1,
            g.large.0,
        );
    }
}

/// Which M_ave the re-run of [`instructions_per_plate_at_m_40_100_200`] under Callgrind grows.
const PLATES_CASE: &str = "HIBI_TEST_GLASS_PLATES";

/// Plates grown per M_ave by [`instructions_per_plate_at_m_40_100_200`].
const COUNTED_PLATES: u64 = 20;

/// Grows the default plate with M_ave = `mean` for seeds 0–19 (counted by Callgrind).
#[unsafe(no_mangle)]
#[inline(never)]
fn hibi_test_glass_plates(mean: f32, memory: &mut hibi_core::glass::GlassStore) -> u64 {
    let mut vertices = 0;
    for seed in 0..COUNTED_PLATES {
        let p = GlassParams { seed, radial_mean: mean, ..GlassParams::default() };
        let mut glass = Glass::new(&p, memory.buffers()).expect("memory suffices");
        while !glass.step(u64::MAX).finished {}
        vertices += u64::from(glass.progress().vertices);
    }
    vertices
}

/// The instructions generation takes per plate (`Glass::new` and stepping to the end) at
/// M_ave = 40, 100 and 200: the mean over seeds 0–19 of the 640² plate, counted by Callgrind
/// (C library `__mem*` left out, as in tests/instructions.rs). Release profile only.
///
///     cargo test --release --test glass instructions_per_plate_at_m_40_100_200 -- --ignored --nocapture
#[test]
#[ignore = "runs Valgrind: about a minute"]
fn instructions_per_plate_at_m_40_100_200() {
    if let Ok(case) = std::env::var(PLATES_CASE) {
        let mean: f32 = case.parse().expect("an M_ave");
        let mut memory = GlassParams::default().memory().expect("valid parameters").allocate();
        println!("\nvertices {}", hibi_test_glass_plates(mean, &mut memory));
        return;
    }
    println!("| M_ave | instructions per plate | vertices per plate |");
    println!("|---|---:|---:|");
    for mean in ["40", "100", "200"] {
        let (stdout, costs) = hibi_tests::callgrind_this_test_by_function(
            "instructions_per_plate_at_m_40_100_200",
            "hibi_test_glass_plates|__mem*",
            (PLATES_CASE, mean),
        );
        let vertices: u64 = stdout
            .lines()
            .find_map(|l| l.strip_prefix("vertices "))
            .and_then(|v| v.trim().parse().ok())
            .unwrap_or_else(|| panic!("M_ave {mean}: no vertex count in\n{stdout}"));
        let count = costs.get("hibi_test_glass_plates").copied().unwrap_or(0);
        assert!(count > 0, "M_ave {mean}: nothing counted");
        println!("| {mean} | {} | {} |", count / COUNTED_PLATES, vertices / COUNTED_PLATES);
    }
}

/// The budget of `step` bounds its work whatever the parameters: every call does at most its
/// budget − 1 + `STEP_PIECE` (every query and face walk resumes where it stopped), and the plate
/// grows the same whatever the budgets.
#[test]
fn step_budgets_bound_the_work() {
    let base = GlassParams::default();
    let cases = [
        ("default", base),
        ("large speed 1e-30", GlassParams { large_speed: 1e-30, ..base }),
        ("huge wander", GlassParams { wander: 1e6, ..base }),
        ("fast cracks", GlassParams { large_speed: 1e6, radial_speed: 1e5, ring_speed: 1e5, ..base }),
        (
            "sector over the whole plate",
            GlassParams { sector_radius: 1e4, sector_angle: std::f32::consts::TAU, ..base },
        ),
    ];
    for (what, p) in cases {
        let m = p.memory().unwrap();
        let mut memory = m.allocate();
        let mut g = Glass::new(&p, memory.buffers()).unwrap();
        let mut worst = 0;
        // Budgets 1 to 200 in turn, to the end of generation: every case ends within 200 000
        // calls (2·10⁷ units), the plate whose large cracks crawl at 1e-30 px a step included.
        for budget in (1..=200).cycle().take(200_000) {
            let before = g.progress().work;
            let progress = g.step(budget);
            let did = g.progress().work - before;
            worst = worst.max(did.saturating_sub(budget));
            assert!(did <= budget - 1 + STEP_PIECE, "{what}: step({budget}) did {did} units");
            if progress.finished {
                break;
            }
        }
        println!("{what}: most work past the budget in one call {worst} units, {} in all", g.progress().work);
        assert!(g.progress().finished, "{what}: not finished after 200 000 calls");
    }
    // Budgets do not change the result.
    let hash = |budget: u64| {
        let m = base.memory().unwrap();
        let mut memory = m.allocate();
        let mut g = Glass::new(&base, memory.buffers()).unwrap();
        while !g.step(budget).finished {}
        let mut bytes = Vec::new();
        for i in 0..g.crack_count() {
            g.for_each_point(i, |q| bytes.extend(q.at.map(f32::to_bits).iter().flat_map(|b| b.to_le_bytes())));
        }
        fnv1a64(&bytes)
    };
    assert_eq!(hash(1), hash(u64::MAX));
    assert_eq!(hash(37), hash(u64::MAX));
}

/// The sum of a plate's fragment rings' signed areas (outer rings positive, holes negative), in
/// f64, and the plate's area W·H.
fn fragment_area(g: &Glass) -> (f64, f64) {
    let p = g.params();
    (fragments_of(g).iter().map(|(r, _)| r.area).sum(), f64::from(p.width) * f64::from(p.height))
}

/// Fragment areas add up to the plate's (relative error at most 1e-4) over many seeds, at the
/// ends of the valid ranges: radial cracks of 1e8 px a step up to `f32::MAX` (too young to
/// turn, they run straight in updates of exactly 10 px, and some land exactly on the edge),
/// the widest and tallest plates with the impact near their far end, and crawling cracks.
/// Plates wider or taller than `MAX_SIDE` (1e15, 1e20, `f32::MAX`) are refused by name.
#[test]
fn fragment_areas_sum_to_the_plate_at_the_ends_of_the_valid_ranges() {
    use hibi_core::glass::{GlassParamError, MAX_SIDE};
    let base = GlassParams::default();
    let mut cases: Vec<(String, GlassParams)> = Vec::new();
    for seed in 0..40 {
        cases.push((format!("default, seed {seed}"), GlassParams { seed, ..base }));
    }
    for radial_speed in [1e8, 1e10, 1e20, 1e30, f32::MAX] {
        for seed in 1..=10 {
            cases.push((
                format!("radial_speed {radial_speed:e}, seed {seed}"),
                GlassParams { radial_speed, seed, ..base },
            ));
        }
    }
    for seed in 1..=5 {
        let wide = GlassParams { width: MAX_SIDE, impact: [MAX_SIDE - 320.0, 320.0], seed, ..base };
        let tall = GlassParams { height: MAX_SIDE, impact: [320.0, MAX_SIDE - 330.0], seed, ..base };
        cases.push((format!("width {MAX_SIDE}, seed {seed}"), wide));
        cases.push((format!("height {MAX_SIDE}, seed {seed}"), tall));
    }
    let square =
        GlassParams { width: MAX_SIDE, height: MAX_SIDE, impact: [MAX_SIDE - 100.0, MAX_SIDE - 200.0], ..base };
    cases.push((format!("{MAX_SIDE} x {MAX_SIDE}"), square));
    for large_speed in [1e-30, 1e-5, 0.01] {
        cases.push((format!("large_speed {large_speed:e}"), GlassParams { large_speed, ..base }));
    }
    cases.push(("ring_speed 1e-30".into(), GlassParams { ring_speed: 1e-30, ..base }));
    for (what, p) in &cases {
        assert_eq!(p.validate(), Ok(()), "{what}");
        let (area, plate) = with_plate(p, |g| fragment_area(g));
        assert!((area - plate).abs() <= 1e-4 * plate, "{what}: fragments cover {area} of {plate} px²");
    }
    println!("{} plates: the fragments cover each", cases.len());
    for side in [MAX_SIDE.next_up(), 131_072.0, 1e15, 1e20, f32::MAX] {
        assert_eq!(GlassParams { width: side, ..base }.validate(), Err(GlassParamError::Size), "width {side}");
        assert_eq!(GlassParams { height: side, ..base }.validate(), Err(GlassParamError::Size), "height {side}");
    }
}

/// Every valid run ends within 1e9 units, its work bounded by the time limit: generation
/// stops after at most `MAX_TIME_STEPS` time steps whatever the speeds, and the time steps in
/// which every growing crack waits (ring cracks whose large cracks crawl) are skipped, not
/// done: large cracks of 1e-30 to 1e-5 px a step finish in under 1e6 units. The most work
/// (printed): every speed 1e-30, all cracks awake and stuck at the impact for the whole time
/// limit.
#[test]
fn every_run_ends_within_its_time_limit() {
    use hibi_core::glass::MAX_TIME_STEPS;
    const MOST: u64 = 1_000_000_000;
    let base = GlassParams::default();
    // Each case, and whether its ring cracks wait past the time limit, in skipped steps.
    let cases = [
        ("large_speed 1e-30", GlassParams { large_speed: 1e-30, ..base }, true),
        ("large_speed 1e-20", GlassParams { large_speed: 1e-20, ..base }, true),
        ("large_speed 1e-6", GlassParams { large_speed: 1e-6, ..base }, true),
        ("large_speed 1e-5", GlassParams { large_speed: 1e-5, ..base }, true),
        ("large_speed 0.01", GlassParams { large_speed: 0.01, ..base }, false),
        ("ring_speed 1e-30", GlassParams { ring_speed: 1e-30, ..base }, false),
        ("radial_speed 1e-30", GlassParams { radial_speed: 1e-30, ..base }, false),
        (
            "every speed 1e-30",
            GlassParams { large_speed: 1e-30, radial_speed: 1e-30, ring_speed: 1e-30, ..base },
            false,
        ),
    ];
    for (what, p, waits) in cases {
        let m = p.memory().unwrap();
        let mut memory = m.allocate();
        let mut g = Glass::new(&p, memory.buffers()).unwrap();
        let mut progress = g.progress();
        while !progress.finished {
            progress = g.step(1_000_000);
            assert!(
                progress.work <= MOST,
                "{what}: {} units at time step {}, not finished",
                progress.work,
                progress.time
            );
        }
        assert!(progress.time <= MAX_TIME_STEPS, "{what}: {progress:?}");
        println!("{what}: {} time steps, {} units", progress.time, progress.work);
        let rings: Vec<usize> = (0..g.crack_count())
            .filter(|&i| matches!(g.crack(i).unwrap().kind, CrackKind::RingClockwise | CrackKind::RingCounterClockwise))
            .collect();
        if waits {
            // The large cracks were enclosed at the impact at once, and the ring cracks wait
            // for them past the time limit: the time steps between are skipped.
            assert_eq!(progress.time, MAX_TIME_STEPS, "{what}");
            assert!(progress.work < 1_000_000, "{what}: {} units", progress.work);
            assert!(rings.iter().all(|&i| points(&g, i).is_empty()), "{what}: a ring crack grew");
        }
        if p.large_speed == 0.01 {
            // Ring cracks wake at ⌈d_i / 0.01⌉ steps, long after every other crack stopped:
            // the skipped steps land exactly on that step, where each starts to grow.
            let grown: Vec<usize> = rings.iter().copied().filter(|&i| !points(&g, i).is_empty()).collect();
            assert!(!grown.is_empty(), "{what}: no ring crack grew");
            for i in grown {
                let (c, first) = (g.crack(i).unwrap(), points(&g, i)[0]);
                assert!(
                    c.wake > 1000 && first.time == c.wake as f32,
                    "{what}: crack {i} woke at {}, starts at {}",
                    c.wake,
                    first.time
                );
            }
        }
    }
}

/// The largest piece of a fragment build's step on `g`, in units: one, and one per half-edge
/// around the vertex a walk reaches (its crack edges, and two border edges).
fn fragment_piece(g: &Glass) -> u64 {
    // (Edges counted at their ends' positions: vertices that share a position are counted
    // together, which can only raise the bound.)
    let mut degree = std::collections::HashMap::<[u32; 2], u64>::new();
    for i in 0..g.crack_count() {
        let mut last: Option<[f32; 2]> = None;
        g.for_each_point(i, |q| {
            if let Some(a) = last {
                for end in [a, q.at] {
                    *degree.entry(end.map(f32::to_bits)).or_default() += 1;
                }
            }
            last = Some(q.at);
        });
    }
    2 + 2 + degree.into_values().max().unwrap_or(0)
}

/// A budgeted fragment build ([`FragmentBuild`]) builds, stepped with any budget, the rings and
/// points `Glass::fragments` writes, bit for bit; each call's work is within its budget and
/// one piece; rings and points copied out in ranges of any length concatenate to the whole;
/// a range past the end is refused, nothing written; and a build whose plate grew meanwhile
/// starts over and builds the new network's fragments. Plates: defaults at several seeds, three
/// impacts, one out of capacity whose fragments hold a hole, and one part way through growth.
#[test]
fn a_budgeted_fragment_build_is_the_fragments_and_its_ranges_concatenate_to_them() {
    let mut plates: Vec<(GlassParams, Vec<[f32; 2]>)> = (0..4)
        .map(|seed| {
            (
                GlassParams { seed, width: 320.0, height: 320.0, impact: [160.0, 160.0], ..GlassParams::default() },
                vec![],
            )
        })
        .collect();
    plates.push((GlassParams { seed: 5, ..GlassParams::default() }, vec![[150.0, 450.0], [500.0, 120.0]]));
    plates.push((GlassParams { seed: 5, max_vertices: 400, ..GlassParams::default() }, vec![]));
    let mut holes = 0;
    for (p, impacts) in &plates {
        with_plate(p, |g| {
            for &at in impacts {
                g.impact(at).unwrap();
                while !g.step(100_000).finished {}
            }
            let whole = fragments(g);
            holes += whole.iter().filter(|(r, _)| r.area < 0.0).count();
            let (rings, points): (Vec<Ring>, Vec<[f32; 2]>) = {
                let (r, p) = g.fragment_counts(&mut scratch(g)).unwrap();
                let mut out = (vec![Ring::default(); r], vec![[0.0f32; 2]; p]);
                g.fragments(&mut scratch(g), &mut out.0, &mut out.1).unwrap();
                out
            };
            let piece = fragment_piece(g);
            let m = g.fragment_build_memory();
            for budget in [1, 7, 1000, u64::MAX] {
                let mut store = m.allocate();
                let mut build = FragmentBuild::new(g, store.buffers()).expect("its memory");
                assert!(build.rings().is_empty() && !build.progress().finished);
                let mut before = 0;
                loop {
                    let progress = build.step(g, budget).expect("the plate it was made for");
                    let done = progress.work - before;
                    assert!(
                        done >= 1 && done < budget.max(1).saturating_add(piece),
                        "{p:?}: {done} units for budget {budget}"
                    );
                    before = progress.work;
                    if progress.finished {
                        assert_eq!((progress.rings, progress.points), (rings.len(), points.len()));
                        break;
                    }
                    assert!(build.rings().is_empty(), "nothing to read before the end");
                }
                assert!(
                    build.rings() == rings.as_slice() && build.points() == points.as_slice(),
                    "{p:?}, budget {budget}"
                );
                // Ranges of any length, concatenated.
                for count in [1, 3, 64] {
                    let (mut r_all, mut p_all) = (Vec::new(), Vec::new());
                    for first in (0..rings.len()).step_by(count) {
                        let mut out = vec![Ring::default(); count.min(rings.len() - first)];
                        build.copy_rings(first, &mut out).unwrap();
                        r_all.extend(out);
                    }
                    for first in (0..points.len()).step_by(count) {
                        let mut out = vec![[0.0f32; 2]; count.min(points.len() - first)];
                        build.copy_points(first, &mut out).unwrap();
                        p_all.extend(out);
                    }
                    assert!(r_all == rings && p_all == points, "ranges of {count}");
                }
                let mut past = vec![Ring { area: 7.0, ..Ring::default() }; 2];
                let refused = build.copy_rings(rings.len() - 1, &mut past);
                assert_eq!(refused, Err(GlassError::BufferTooSmall { needed: rings.len() }));
                assert!(past.iter().all(|r| r.area == 7.0), "nothing written");
            }
        });
    }
    assert!(holes > 0, "a plate with a hole");
    // A build begun on a plate part way through growth, which then grows on, starts over.
    let p = GlassParams { seed: 6, ..GlassParams::default() };
    let mut memory = p.memory().unwrap().allocate();
    let mut g = Glass::new(&p, memory.buffers()).unwrap();
    g.step(20_000);
    let mut store = g.fragment_build_memory().allocate();
    let mut build = FragmentBuild::new(&g, store.buffers()).unwrap();
    let early = build.step(&g, 500).unwrap();
    assert!(!early.finished && early.work >= 500);
    while !g.step(100_000).finished {}
    let restarted = build.step(&g, 10).unwrap();
    assert!(restarted.work < 10 + fragment_piece(&g), "{restarted:?}: started over");
    let end = build.run(&g).unwrap();
    assert!(end.finished);
    let whole = fragments_of(&g);
    assert_eq!(build.rings().len(), whole.len());
    for (r, (ring, pts)) in build.rings().iter().zip(&whole) {
        assert!(r == ring && &build.points()[r.first_point as usize..][..r.point_count as usize] == pts.as_slice());
    }
}
