//! Model B against the paper's facts (Agui et al.) and the acceptance list.

use hibi_core::glass::{CrackEnd, CrackKind, CrackPoint, Glass, GlassBuffers, GlassError, GlassParams};
use hibi_tests::fnv1a64;

/// Runs `params` to the end of generation and hands the plate to `inspect`.
fn with_plate<R>(params: &GlassParams, inspect: impl FnOnce(&mut Glass) -> R) -> R {
    let m = params.memory().expect("valid parameters");
    let (mut cracks, mut vertices) = (vec![Default::default(); m.cracks], vec![Default::default(); m.vertices]);
    let (mut edges, mut words) = (vec![Default::default(); m.edges], vec![0u32; m.words]);
    let buffers = GlassBuffers { cracks: &mut cracks, vertices: &mut vertices, edges: &mut edges, words: &mut words };
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
                    CrackEnd::Generation => {}
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
    assert_eq!(hash, 15194608960451595373, "the glass scene changed");
}

#[test]
fn rasters_draw_the_network_and_date_its_pixels() {
    use hibi_core::glass::GlassRender;
    use hibi_core::raster::RasterError;
    let p = GlassParams { seed: 3, ..GlassParams::default() };
    with_plate(&p, |g| {
        let render = GlassRender { width: 320, height: 320, ..GlassRender::default() };
        let (mut mask, mut time) = (vec![0u8; 320 * 320], vec![0.0f32; 320 * 320]);
        g.render_mask(&render, &mut mask).unwrap();
        g.render_time(&render, &mut time).unwrap();
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
        assert_eq!(g.render_mask(&render, &mut untouched), Err(RasterError::BufferTooSmall { needed: 320 * 320 }));
        assert!(untouched.iter().all(|&v| v == 9));
        let thin = GlassRender { line_width: 0.0, ..render };
        assert_eq!(g.render_mask(&thin, &mut mask), Err(RasterError::LineWidth));
    });
}
