//! Model B against the paper's facts (Agui et al.) and the acceptance list.

use hibi_core::glass::{CrackEnd, CrackKind, CrackPoint, FragmentRing, Glass, GlassBuffers, GlassError, GlassParams};
use hibi_tests::{GlassVecs, fnv1a64};

/// Runs `params` to the end of generation and hands the plate to `inspect`.
fn with_plate<R>(params: &GlassParams, inspect: impl FnOnce(&mut Glass) -> R) -> R {
    let m = params.memory().expect("valid parameters");
    let mut memory = GlassVecs::new(&m);
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
    assert_eq!(hash, 15163377400841267211, "the glass scene changed");
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

/// The fragments of a plate: ring records and each ring's points.
fn fragments(g: &mut Glass) -> Vec<(FragmentRing, Vec<[f32; 2]>)> {
    let (rings, points) = g.fragment_counts();
    let mut out = (vec![FragmentRing::default(); rings], vec![[0.0f32; 2]; points]);
    assert_eq!(g.fragments(&mut out.0, &mut out.1), Ok((rings, points)));
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
fn assert_fragments_tile(p: &GlassParams, frags: &[(FragmentRing, Vec<[f32; 2]>)], what: &str) {
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
    let p = GlassParams { seed: 5, max_vertices: 300, ..GlassParams::default() };
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
    let mut memory = GlassVecs::new(&m);
    let buffers = memory.buffers();
    let mut g = Glass::new(&p, buffers).unwrap();
    for _ in 0..4 {
        g.step(150);
        assert_fragments_tile(&p, &fragments(&mut g), "mid-growth");
    }
}

#[test]
fn fragments_are_written_only_into_buffers_that_fit() {
    with_plate(&GlassParams { seed: 2, ..GlassParams::default() }, |g| {
        let (rings, points) = g.fragment_counts();
        let mut short = (vec![FragmentRing::default(); rings], vec![[9.0f32; 2]; points - 1]);
        assert_eq!(g.fragments(&mut short.0, &mut short.1), Err(GlassError::BufferTooSmall { needed: points }));
        assert!(short.0.iter().all(|r| *r == FragmentRing::default()) && short.1.iter().all(|q| *q == [9.0; 2]));
        let mut short = (vec![FragmentRing::default(); rings - 1], vec![[9.0f32; 2]; points]);
        assert_eq!(g.fragments(&mut short.0, &mut short.1), Err(GlassError::BufferTooSmall { needed: rings }));
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
