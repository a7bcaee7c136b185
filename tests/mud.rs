//! Model A against the paper's claims (Hirota et al.), hibi's own acceptance criteria, and the
//! golden snapshots. These run the model at size; hibi-core is optimised in every profile.

use hibi_core::mud::{
    Boundary, CrackStatistics, Mud, MudBuffers, MudLayers, MudParams, MudProgress, MudRender, Solver, Topology,
};
use hibi_core::scalar::{Q16, Scalar};
use hibi_tests::fnv1a64;

/// Runs `params` to its end on backend `S`; returns the statistics and the segments' hash.
fn run<S: Scalar>(params: &MudParams) -> (CrackStatistics, u64, Vec<hibi_core::mud::CrackSegment>) {
    let memory = params.memory().expect("valid parameters");
    let (mut scalars, mut words) = (vec![S::ZERO; memory.scalars], vec![0u32; memory.words]);
    let mut mud = Mud::new(params, MudBuffers { scalars: &mut scalars, words: &mut words }).expect("memory suffices");
    assert!(mud.run().unwrap().finished);
    let stats = mud.statistics();
    let mut segments = vec![Default::default(); mud.segment_count()];
    mud.segments(&mut segments).expect("buffer suffices");
    let bytes: Vec<u8> = segments
        .iter()
        .flat_map(|s| [s.start, s.end, s.width, s.time].into_iter().flatten().flat_map(|v| v.to_bits().to_le_bytes()))
        .collect();
    (stats, fnv1a64(&bytes), segments)
}

fn params(size: u32) -> MudParams {
    MudParams { columns: size, rows: size, ..MudParams::default() }
}

fn mean(values: impl Iterator<Item = f32>) -> f32 {
    let v: Vec<f32> = values.collect();
    v.iter().sum::<f32>() / v.len() as f32
}

fn within(a: f32, b: f32, tolerance: f32) -> bool {
    (a - b).abs() <= tolerance * a.max(b)
}

/// Mean crack density and mean cell area of each solver (explicit, quasi-static) over seeds
/// 1..=`seeds` on a `size`² lattice, printed.
fn solver_means(seeds: u64, topology: Topology, size: u32) -> ((f32, f32), (f32, f32)) {
    let mut explicit = Vec::new();
    let mut fast = Vec::new();
    for seed in 1..=seeds {
        let p = MudParams { seed, topology, ..params(size) };
        explicit.push(run::<f32>(&MudParams { solver: Solver::Explicit, ..p }).0);
        fast.push(run::<f32>(&MudParams { solver: Solver::QuasiStatic, ..p }).0);
    }
    let density = (mean(explicit.iter().map(|s| s.crack_density)), mean(fast.iter().map(|s| s.crack_density)));
    let area = (mean(explicit.iter().map(|s| s.mean_cell_area)), mean(fast.iter().map(|s| s.mean_cell_area)));
    println!(
        "{topology:?} {size}², seeds 1-{seeds}: crack density explicit {:.4} quasi-static {:.4}",
        density.0, density.1
    );
    println!(
        "{topology:?} {size}², seeds 1-{seeds}: mean cell area explicit {:.2} quasi-static {:.2} cm²",
        area.0, area.1
    );
    (density, area)
}

/// Measured on the traced network. With the quasi-static node updates over-relaxed (1.2) the
/// mean cell areas were 19 % apart; plain Gauss–Seidel brings them within 15 % (see
/// `quasi_static.rs`).
#[test]
fn explicit_and_quasi_static_agree_over_eight_seeds() {
    // The irregular lattice's explicit run goes spring by spring, about ten times slower
    // than the hexagonal one's vectorised rows: a smaller plate.
    for (topology, size) in [(Topology::Hexagonal, 48), (Topology::Irregular, 32)] {
        let (density, area) = solver_means(8, topology, size);
        assert!(within(density.0, density.1, 0.15), "{topology:?}: crack density {density:?}");
        assert!(within(area.0, area.1, 0.15), "{topology:?}: mean cell area {area:?}");
    }
}

/// The same over 24 seeds (about a minute in release, so only on request:
/// `cargo test --release --test mud -- --ignored --nocapture`).
#[test]
#[ignore = "a minute in release: the solvers' agreement over seeds 1-24"]
fn explicit_and_quasi_static_over_twenty_four_seeds() {
    let (density, area) = solver_means(24, Topology::Hexagonal, 48);
    assert!(within(density.0, density.1, 0.15), "crack density {density:?}");
    assert!(within(area.0, area.1, 0.15), "mean cell area {area:?}");
}

/// The share of crack length in each 15° orientation bin, and the effective fraction of
/// bins it occupies (exp(entropy)/bins: 1 for a uniform spread).
fn orientation_spread(segments: &[hibi_core::mud::CrackSegment]) -> f32 {
    let mut bins = [0.0f32; 12];
    for s in segments {
        let (dx, dy) = (s.end[0] - s.start[0], s.end[1] - s.start[1]);
        let length = dx.hypot(dy);
        if length == 0.0 {
            continue;
        }
        let angle = dy.atan2(dx).rem_euclid(std::f32::consts::PI);
        // Centre the bins on multiples of 15° so lattice directions fall mid-bin.
        let bin = ((angle / std::f32::consts::PI * 12.0 + 0.5) as usize) % 12;
        bins[bin] += length;
    }
    let total: f32 = bins.iter().sum();
    let entropy: f32 = bins.iter().filter(|&&b| b > 0.0).map(|&b| -(b / total) * (b / total).ln()).sum();
    entropy.exp() / 12.0
}

#[test]
fn hexagonal_patterns_are_more_isotropic_than_square_ones() {
    let hex = run::<f32>(&params(64)).2;
    let square = run::<f32>(&MudParams { topology: Topology::Square, target_shrink: 0.03, ..params(64) }).2;
    let (h, s) = (orientation_spread(&hex), orientation_spread(&square));
    println!("orientation spread: hexagonal {h:.3}, square {s:.3}");
    assert!(h > s + 0.1, "hexagonal {h} vs square {s}");
}

/// Paper §3 / Fig. 8: the 1-D model predicts the crack spacing D from the layers' moduli and
/// the shrink. Softening the shear layer (E/G from 2.5 to 5 to 10) widens D, and the cells'
/// size tracks it: √(mean cell area) / D stays within 15 % of its mean over the three (seeds
/// 1-4 each, 64² hex).
#[test]
fn a_stiffer_surface_spaces_cracks_wider_as_the_one_dimensional_model_predicts() {
    let base = params(64);
    let figures = [4.0e5f32, 2.0e5, 1.0e5].map(|shear_modulus| {
        let p = MudParams { shear_modulus, ..base };
        let d = p.predicted_spacing(p.target_shrink).unwrap().spacing;
        let area = mean((1..=4).map(|seed| run::<f32>(&MudParams { seed, ..p }).0.mean_cell_area));
        (d, area)
    });
    let ratios = figures.map(|(d, area)| area.sqrt() / d);
    println!("E/G 2.5, 5, 10: (predicted D cm, mean cell area cm²) {figures:?}; √area / D {ratios:?}");
    for k in 0..2 {
        assert!(figures[k + 1].0 > figures[k].0 && figures[k + 1].1 > figures[k].1 * 1.2, "{figures:?}");
    }
    let m = mean(ratios.iter().copied());
    assert!(ratios.iter().all(|&r| within(r, m, 0.15)), "√area / D {ratios:?}");
}

/// Paper §4.2 (Fig. 9): the same physical parameters meshed finer give cells of about the
/// same size in cm, so a coarse mesh previews a fine one. The plate is the `fig9a`–`fig9c`
/// presets' square 64 cm one, meshed at W = 2, 1 and 0.5 cm, measured on the traced network
/// over 16 seeds. The paper's rule (κ̄ at every W) does not keep it: 0.41 / 0.55 / 0.75 cracks
/// per cm and 30.3 / 18.4 / 10.3 cm² cells. The presets scale the break margin to the element
/// size (`break_stretch_size_exponent` 0.25), which does.
#[test]
fn halving_the_element_size_keeps_crack_density_and_cell_area() {
    let figures = ["fig9a", "fig9b", "fig9c"].map(|name| {
        let base = hibi_core::mud::preset(name).expect("a preset");
        assert_eq!(base.break_stretch_size_exponent, 0.25);
        let runs: Vec<CrackStatistics> = (1..=16).map(|seed| run::<f32>(&MudParams { seed, ..base }).0).collect();
        let density = mean(runs.iter().map(|s| s.crack_density));
        let area = mean(runs.iter().map(|s| s.mean_cell_area));
        println!(
            "{name} (W = {} cm), seeds 1-16: {density:.3} cracks per cm, cells of {area:.1} cm²",
            base.element_size
        );
        (density, area)
    });
    for k in 0..2 {
        let (a, b) = (figures[k], figures[k + 1]);
        assert!(within(a.0, b.0, 0.15), "crack density, step {k}: {figures:?}");
        assert!(within(a.1, b.1, 0.15), "mean cell area, step {k}: {figures:?}");
    }
}

#[test]
fn periodic_rasters_are_seamless() {
    // Rendered with the view panned by half a period, a seamless tile is the same picture
    // rolled by half: its edges now meet in the middle.
    let p = params(64);
    let memory = p.memory().unwrap();
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let mut mud = Mud::new(&p, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
    mud.run().unwrap();
    let [w, h] = mud.lattice().extent();
    let render = MudRender { width: 256, height: 256, ..MudRender::default() };
    let mut tile = vec![0u8; 256 * 256];
    mud.render(&render, MudLayers { mask: Some(&mut tile), ..Default::default() }).unwrap();
    let mut panned = vec![0u8; 256 * 256];
    mud.render(
        &MudRender { offset: [w / 2.0, h / 2.0], ..render },
        MudLayers { mask: Some(&mut panned), ..Default::default() },
    )
    .unwrap();
    let mut worst = 0u8;
    let mut total = 0u64;
    for y in 0..256 {
        for x in 0..256 {
            let a = tile[((y + 128) % 256) * 256 + (x + 128) % 256];
            let b = panned[y * 256 + x];
            worst = worst.max(a.abs_diff(b));
            total += u64::from(a.abs_diff(b));
        }
    }
    assert!(tile.iter().filter(|&&v| v > 128).count() > 2000, "the tile has cracks");
    assert!(worst <= 2 && total < 256 * 256 / 8, "panned tile differs: worst {worst}, total {total}");
    // An open lattice is not seamless: the same comparison fails.
    let open = MudParams { boundary: Boundary::Open, ..p };
    let memory = open.memory().unwrap();
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let mut mud = Mud::new(&open, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
    mud.run().unwrap();
    mud.render(&render, MudLayers { mask: Some(&mut tile), ..Default::default() }).unwrap();
    mud.render(
        &MudRender { offset: [w / 2.0, h / 2.0], ..render },
        MudLayers { mask: Some(&mut panned), ..Default::default() },
    )
    .unwrap();
    let differs =
        (0..256 * 256).filter(|&i| tile[((i / 256 + 128) % 256) * 256 + (i % 256 + 128) % 256] != panned[i]).count();
    assert!(differs > 1000, "{differs}");
}

#[test]
fn fixed_point_and_float_agree_on_crack_statistics() {
    let p = params(64);
    let float = run::<f32>(&p).0;
    let fixed = run::<Q16>(&p).0;
    println!("f32 {float:?}\nQ16 {fixed:?}");
    assert!(within(float.crack_density, fixed.crack_density, 0.20), "{float:?} vs {fixed:?}");
    assert!(within(float.mean_cell_area, fixed.mean_cell_area, 0.20), "{float:?} vs {fixed:?}");
}

/// The golden scene: the default parameters on a 64×64 lattice.
#[test]
fn golden_segments() {
    let p = params(64);
    assert_eq!(run::<f32>(&p).1, 16368562623663613091, "the f32 scene changed");
    assert_eq!(run::<Q16>(&p).1, 17237121318573303088, "the Q16.16 scene changed");
    let irregular = MudParams { topology: Topology::Irregular, ..p };
    assert_eq!(run::<f32>(&irregular).1, 13504295807150344760, "the irregular f32 scene changed");
    assert_eq!(run::<Q16>(&irregular).1, 162765407330835635, "the irregular Q16.16 scene changed");
}

/// The share of crack length within 30° of `direction`.
fn share_along(segments: &[hibi_core::mud::CrackSegment], direction: f32) -> f32 {
    let (mut along, mut total) = (0.0, 0.0);
    for s in segments {
        let (dx, dy) = (s.end[0] - s.start[0], s.end[1] - s.start[1]);
        let length = dx.hypot(dy);
        let angle = (dy.atan2(dx) - direction).rem_euclid(std::f32::consts::PI);
        total += length;
        if !(std::f32::consts::FRAC_PI_6..=5.0 * std::f32::consts::FRAC_PI_6).contains(&angle) {
            along += length;
        }
    }
    along / total
}

#[test]
fn anisotropic_break_stretch_orients_the_cracks() {
    // Paper Fig. 7: springs across the preferred direction break first, so cracks run along it.
    let isotropic = share_along(&run::<f32>(&params(64)).2, 0.0);
    let horizontal = share_along(&run::<f32>(&MudParams { anisotropy_ratio: 4.0, ..params(64) }).2, 0.0);
    let vertical = MudParams { anisotropy_ratio: 4.0, anisotropy_direction: std::f32::consts::FRAC_PI_2, ..params(64) };
    let vertical = share_along(&run::<f32>(&vertical).2, std::f32::consts::FRAC_PI_2);
    println!(
        "share within 30° of the preferred direction: isotropic {isotropic:.2}, φ = 0: {horizontal:.2}, φ = 90°: {vertical:.2}"
    );
    assert!(horizontal > isotropic + 0.15 && vertical > isotropic + 0.15);
}

#[test]
fn a_growing_deep_layer_cracks_the_surface_like_shrinking_does() {
    // Growth (tree bark) is the same misfit seen from the deep layer: similar cells, drawn in
    // the growing frame.
    let shrink = run::<f32>(&params(64)).0;
    let growth = run::<f32>(&MudParams { drive: hibi_core::mud::Drive::Growth, ..params(64) }).0;
    println!("shrink {shrink:?}\ngrowth {growth:?}");
    assert!(growth.cells > 1 && within(shrink.crack_density, growth.crack_density, 0.25), "{shrink:?} vs {growth:?}");
}

#[test]
fn step_does_bounded_work_and_resumes_to_the_same_result() {
    for solver in [Solver::QuasiStatic, Solver::Explicit] {
        let p = MudParams { solver, target_shrink: 0.018, ..params(24) };
        let memory = p.memory().unwrap();
        let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
        let mut mud = Mud::new(&p, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
        // One piece is a row's springs in one direction and their rescan for breaks
        // (explicit), one node's springs (quasi-static, hexagonal) or a piece of the
        // network's tracing.
        let piece = if solver == Solver::Explicit { 2 * u64::from(p.columns) } else { 6 };
        let piece = piece.max(hibi_core::mud::TRACE_PIECE);
        let budget = 5_000;
        let mut before = 0;
        let mut calls = 0;
        loop {
            let progress = mud.step(budget).unwrap();
            let bound = budget - 1 + piece;
            assert!(progress.work - before <= bound, "{solver:?}: {} > {bound}", progress.work - before);
            before = progress.work;
            calls += 1;
            if progress.finished {
                break;
            }
        }
        assert!(calls > 10, "{solver:?} finished in {calls} calls");
        let mut stepped = vec![Default::default(); mud.segment_count()];
        mud.segments(&mut stepped).unwrap();
        // The same run in one call gives the same cracks.
        let (_, _, whole) = run::<f32>(&p);
        assert!(stepped == whole, "{solver:?}: stepping changed the result");
    }
}

#[test]
fn a_run_can_end_at_a_target_crack_density() {
    let p = MudParams { target_shrink: 0.0, target_crack_density: 0.2, ..params(48) };
    let memory = p.memory().unwrap();
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let mut mud = Mud::new(&p, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
    let end = mud.run().unwrap();
    assert!(end.finished && end.crack_density >= 0.2 && end.crack_density < 0.25, "{end:?}");
    assert!(end.shrink < 0.023, "{end:?}");
}

#[test]
fn the_time_map_dates_every_crack_pixel_and_only_those() {
    let p = params(48);
    let memory = p.memory().unwrap();
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let mut mud = Mud::new(&p, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
    let end = mud.run().unwrap();
    let render = MudRender { width: 192, height: 192, ..MudRender::default() };
    let (mut mask, mut time, mut height) = (vec![0u8; 192 * 192], vec![0.0f32; 192 * 192], vec![0.0f32; 192 * 192]);
    mud.render(&render, MudLayers { mask: Some(&mut mask), ..Default::default() }).unwrap();
    mud.render(&render, MudLayers { time: Some(&mut time), ..Default::default() }).unwrap();
    mud.render(&render, MudLayers { height: Some(&mut height), ..Default::default() }).unwrap();
    for i in 0..192 * 192 {
        if mask[i] >= 128 {
            assert!(time[i].is_finite() && time[i] > 0.0 && time[i] <= end.time, "pixel {i}: {}", time[i]);
            assert!(height[i] < 1.0, "pixel {i} is cracked but not grooved");
        }
        if mask[i] == 0 {
            assert!(time[i].is_infinite(), "pixel {i}");
        }
    }
    // Cells are raised: their middles are at full height, their bevelled edges and the
    // grooves below it (at 4 px per spacing, a third of this small plate is cell middle).
    let surface = height.iter().filter(|&&h| h == 1.0).count();
    assert!(surface > 192 * 192 / 4, "{surface}");
    // Cracks appear over time: the earliest and latest cracked pixels are far apart in time.
    let times: Vec<f32> = time.iter().copied().filter(|t| t.is_finite()).collect();
    let (first, last) = times.iter().fold((f32::MAX, 0.0f32), |(a, b), &t| (a.min(t), b.max(t)));
    assert!(last - first > 10.0, "{first}..{last}");
}

/// The traced network of a finished run: vertices, edges and points.
struct Network {
    vertices: Vec<hibi_core::mud::NetworkVertex>,
    edges: Vec<hibi_core::mud::NetworkEdge>,
    points: Vec<hibi_core::mud::NetworkPoint>,
}

fn network(params: &MudParams) -> Network {
    let memory = params.memory().expect("valid parameters");
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let mut mud = Mud::new(params, MudBuffers { scalars: &mut scalars, words: &mut words }).expect("memory suffices");
    assert!(mud.run().unwrap().finished);
    let counts = mud.network_counts();
    let mut n = Network {
        vertices: vec![Default::default(); counts.vertices],
        edges: vec![Default::default(); counts.edges],
        points: vec![Default::default(); counts.points],
    };
    assert_eq!(mud.network(&mut n.vertices, &mut n.edges, &mut n.points), Ok(counts));
    n
}

impl Network {
    fn polyline(&self, e: &hibi_core::mud::NetworkEdge) -> &[hibi_core::mud::NetworkPoint] {
        &self.points[e.first_point as usize..][..e.point_count as usize]
    }

    fn length(&self, e: &hibi_core::mud::NetworkEdge) -> f32 {
        self.polyline(e).windows(2).map(|w| (w[1].at[0] - w[0].at[0]).hypot(w[1].at[1] - w[0].at[1])).sum()
    }

    /// The share of crack length in the largest connected piece.
    fn largest_piece_share(&self) -> f32 {
        let n = self.vertices.len();
        let mut parent: Vec<usize> = (0..n).collect();
        fn find(p: &mut [usize], mut x: usize) -> usize {
            while p[x] != x {
                p[x] = p[p[x]];
                x = p[x];
            }
            x
        }
        for e in &self.edges {
            if e.from != hibi_core::mud::NO_VERTEX {
                let (a, b) = (find(&mut parent, e.from as usize), find(&mut parent, e.to as usize));
                parent[a] = b;
            }
        }
        let mut length = vec![0.0f32; n];
        let mut total = 0.0;
        let mut closed = 0.0f32;
        for e in &self.edges {
            let l = self.length(e);
            total += l;
            if e.from == hibi_core::mud::NO_VERTEX {
                closed = closed.max(l);
            } else {
                let r = find(&mut parent, e.from as usize);
                length[r] += l;
            }
        }
        length.iter().copied().fold(closed, f32::max) / total
    }

    /// Dead ends (degree 1, not on the border) over vertices of degree other than 2.
    fn dead_end_share(&self) -> f32 {
        let dead = self.vertices.iter().filter(|v| v.degree == 1 && v.on_border == 0).count();
        dead as f32 / self.vertices.iter().filter(|v| v.degree != 2).count() as f32
    }
}

#[test]
fn the_network_is_one_connected_thing() {
    for (topology, seed) in
        [Topology::Hexagonal, Topology::Irregular].into_iter().flat_map(|t| (1..=8).map(move |s| (t, s)))
    {
        let n = network(&MudParams { seed, topology, ..MudParams::default() });
        let (share, dead) = (n.largest_piece_share(), n.dead_end_share());
        println!(
            "{topology:?} seed {seed}: {} vertices, {} edges; largest piece {:.1} % of crack length, dead ends {:.1} %",
            n.vertices.len(),
            n.edges.len(),
            100.0 * share,
            100.0 * dead
        );
        assert!(share >= 0.90, "{topology:?} seed {seed}: {share}");
        // At most 10 % dead ends. The separation rule alone leaves 12-15 % on the hexagonal
        // lattice and 25-27 % on the irregular one: tips one node short of another crack,
        // and dead ends that have not opened (see network.rs, rule 1).
        assert!(dead <= 0.10, "{topology:?} seed {seed}: {dead}");
        // Every edge joins its vertices: its first and last points are theirs.
        for e in &n.edges {
            let p = n.polyline(e);
            assert!(p.len() >= 2);
            if e.from != hibi_core::mud::NO_VERTEX {
                assert_eq!(p[0].at, n.vertices[e.from as usize].at);
            }
        }
    }
}

/// At the default end (2.3 % shrink) the network is still growing: run on, its tips join up
/// and the dead ends fall further, while the cells shrink (the figures in the guide's mud page; seeds 1-8).
#[test]
fn dead_ends_join_up_as_the_network_grows() {
    let figures = [0.023f32, 0.024, 0.025].map(|target_shrink| {
        let (mut dead, mut area) = (0.0, 0.0);
        for seed in 1..=8 {
            let p = MudParams { seed, target_shrink, ..MudParams::default() };
            dead += network(&p).dead_end_share() / 8.0;
            area += run::<f32>(&p).0.mean_cell_area / 8.0;
        }
        println!("end shrink {target_shrink}: dead ends {:.1} %, cells of {area:.1} cm²", 100.0 * dead);
        (dead, area)
    });
    assert!(figures[0].0 <= 0.10, "{figures:?}");
    assert!(figures.windows(2).all(|w| w[1].0 < w[0].0 && w[1].1 < w[0].1), "{figures:?}");
}

/// The cells of a finished run: rings and their points, and the lattice's extent.
fn cells(params: &MudParams) -> (hibi_core::mud::CellCounts, Vec<hibi_core::polygon::Ring>, Vec<[f32; 2]>, [f32; 2]) {
    cells_on::<f32>(params)
}

/// The cells of a finished run on backend `S`: rings and their points, and the plate's
/// period in the frame the cells are drawn in (the lattice's extent, times the deep layer's
/// factor 1 + misfit under the growth drive: the pattern is drawn in the growing frame).
fn cells_on<S: Scalar>(
    params: &MudParams,
) -> (hibi_core::mud::CellCounts, Vec<hibi_core::polygon::Ring>, Vec<[f32; 2]>, [f32; 2]) {
    let memory = params.memory().expect("valid parameters");
    let (mut scalars, mut words) = (vec![S::ZERO; memory.scalars], vec![0u32; memory.words]);
    let mut mud = Mud::new(params, MudBuffers { scalars: &mut scalars, words: &mut words }).expect("memory suffices");
    // In calls of a million units, a thousand at most: a run that does not end fails here.
    let mut end = mud.progress();
    for _ in 0..1000 {
        end = mud.step(1_000_000).unwrap();
        if end.finished {
            break;
        }
    }
    assert!(end.finished, "{params:?}: {end:?}");
    let counts = mud.cell_counts();
    let (mut rings, mut points) = (vec![Default::default(); counts.rings], vec![[0.0; 2]; counts.points]);
    assert_eq!(mud.cells(&mut rings, &mut points), Ok(counts));
    let deep = if params.drive == hibi_core::mud::Drive::Growth { 1.0 + end.shrink } else { 1.0 };
    (counts, rings, points, mud.lattice().extent().map(|e| e * deep))
}

/// The cells' signed areas (outer rings positive, holes negative) add up to the periodic
/// plate's area within 1e-4 of it, summed in f64, on both backends, both solvers, the
/// hexagonal and irregular lattices over several seeds, and at the extremes the validation
/// accepts: the smallest periodic lattices, and misfits run to the largest the model follows
/// (shrink 0.99, growth 100, where the cells are single elements) and drawn in the growing
/// frame. A region that wraps around the torus has no ring (`CellCounts::wrapping` counts its
/// wrapping boundaries; the holes in it name `IN_WRAPPING_CELL`): where one is left, the rings
/// add up to less than the plate by its area. No cell is a crumb at the default shrink.
#[test]
fn cells_are_polygons_whose_areas_add_up_to_the_plate() {
    use Topology::{Hexagonal, Irregular, Square};
    use hibi_core::mud::{CellCounts, Drive, IN_WRAPPING_CELL};
    use hibi_core::polygon::Ring;
    /// Checks one run's cells; returns whether the rings cover the whole plate.
    fn check(name: &str, (counts, rings, points, [w, h]): (CellCounts, Vec<Ring>, Vec<[f32; 2]>, [f32; 2])) -> bool {
        let plate = f64::from(w) * f64::from(h);
        let total: f64 = rings.iter().map(|r| r.area).sum();
        let outer = rings.iter().filter(|r| r.area > 0.0).count();
        // Every ring has at least three points; holes name the outer ring they lie in, or
        // the wrapping region.
        assert_eq!(rings.iter().map(|r| r.point_count as usize).sum::<usize>(), points.len(), "{name}");
        let mut in_wrapping = false;
        for r in &rings {
            assert!(r.point_count >= 3, "{name}: {r:?}");
            if r.area < 0.0 {
                in_wrapping |= r.hole_of == IN_WRAPPING_CELL;
                assert!(r.hole_of == IN_WRAPPING_CELL || rings[r.hole_of as usize].area > 0.0, "{name}: {r:?}");
            } else {
                assert_eq!(r.hole_of, u32::MAX, "{name}: {r:?}");
            }
        }
        let wraps = counts.wrapping > 0 || in_wrapping || rings.is_empty();
        println!(
            "{name}: {outer} cells, {} holes, {} wrapping; area {total:.4} of {plate:.4}",
            counts.rings - outer,
            counts.wrapping
        );
        if wraps {
            assert!(total < plate, "{name}: a wrapping region is left, yet the rings cover {total} of {plate}");
        } else {
            assert!((total - plate).abs() <= 1e-4 * plate, "{name}: {total} of {plate}");
        }
        !wraps
    }
    let (mut runs, mut covered) = (0, 0);
    // The default plate, quasi-static, on both backends.
    for (topology, seed) in [Hexagonal, Irregular].into_iter().flat_map(|t| (1..=8).map(move |s| (t, s))) {
        let p = MudParams { seed, topology, ..MudParams::default() };
        for (backend, run) in [("f32", cells_on::<f32> as fn(&MudParams) -> _), ("Q16", cells_on::<Q16>)] {
            if backend == "Q16" && seed > 2 {
                continue;
            }
            let (counts, rings, points, period) = run(&p);
            // No crumbs: no cell is one node. The crack points are smoothed along the cracks,
            // which rounds a small cell's outline in: a one-node cell (√3/2 spacing² on the
            // lattice) measures about 0.2 spacing² (with rule 2 switched off, seed 1's smallest
            // is 0.20), a two-node one 0.86 or more; the irregular lattice's smallest Voronoi
            // cells are a third of an element.
            let smallest = rings.iter().filter(|r| r.area > 0.0).map(|r| r.area).fold(f64::INFINITY, f64::min);
            let crumb = if topology == Hexagonal { 0.5 } else { 0.3 };
            assert!(smallest > crumb, "{topology:?} seed {seed} {backend}: a cell of {smallest}");
            assert_eq!(counts.wrapping, 0, "{topology:?} seed {seed} {backend}");
            runs += 1;
            covered += usize::from(check(
                &format!("{topology:?} 128² seed {seed} {backend}"),
                (counts, rings, points, period),
            ));
        }
    }
    // Both solvers on smaller plates (the explicit solver integrates every short step), and
    // the extremes: the smallest periodic lattices, and the largest misfits in a few long
    // steps.
    let explicit = MudParams { solver: Solver::Explicit, ..MudParams::default() };
    let to_the_end = MudParams { target_shrink: 0.0, shrink_ratio: 0.9, ..explicit };
    let mut cases = Vec::new();
    for solver in [Solver::Explicit, Solver::QuasiStatic] {
        for seed in 1..=3 {
            cases.push(MudParams { solver, seed, columns: 16, rows: 16, ..explicit });
            cases.push(MudParams { solver, seed, topology: Irregular, columns: 12, rows: 12, ..explicit });
            // Early, and with cracks along one direction preferred: some regions may still
            // wrap around the torus (the explicit run of seed 3 leaves two wrapping boundaries
            // in f32).
            let early = MudParams { target_shrink: 0.016, anisotropy_ratio: 8.0, ..explicit };
            cases.push(MudParams { solver, seed, columns: 16, rows: 16, ..early });
        }
        for drive in [Drive::Shrink, Drive::Growth] {
            for (topology, columns, rows) in [(Hexagonal, 3, 4), (Square, 3, 3), (Irregular, 8, 8), (Hexagonal, 16, 16)]
            {
                cases.push(MudParams { solver, drive, topology, columns, rows, ..to_the_end });
            }
        }
    }
    for p in &cases {
        let name = |backend: &str| {
            format!("{:?} {:?} {:?} {}×{} seed {} {backend}", p.solver, p.drive, p.topology, p.columns, p.rows, p.seed)
        };
        runs += 2;
        covered += usize::from(check(&name("f32"), cells_on::<f32>(p)));
        covered += usize::from(check(&name("Q16"), cells_on::<Q16>(p)));
    }
    // The sums were checked, not only that wrapping regions are short of the plate.
    assert!(10 * covered >= 9 * runs, "{covered} of {runs} runs covered their plate");
}

/// The first proper crossing (the two segments' interiors meet at one point) between two
/// edges of a ring, or of a ring and a hole in it: (ring, edge, ring, edge). Computed in f64.
fn ring_crossing(rings: &[hibi_core::polygon::Ring], points: &[[f32; 2]]) -> Option<[usize; 4]> {
    let at = |r: &hibi_core::polygon::Ring| -> Vec<[f64; 2]> {
        points[r.first_point as usize..(r.first_point + r.point_count) as usize]
            .iter()
            .map(|p| p.map(f64::from))
            .collect()
    };
    let twice = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    let crosses = |a, b, c, d| twice(a, b, c) * twice(a, b, d) < 0.0 && twice(c, d, a) * twice(c, d, b) < 0.0;
    for (i, ring) in rings.iter().enumerate() {
        let q = at(ring);
        let n = q.len();
        for a in 0..n {
            for b in a + 2..n {
                if !(a == 0 && b == n - 1) && crosses(q[a], q[(a + 1) % n], q[b], q[(b + 1) % n]) {
                    return Some([i, a, i, b]);
                }
            }
        }
        for (h, hole) in rings.iter().enumerate().filter(|(_, h)| h.hole_of as usize == i) {
            let o = at(hole);
            for a in 0..n {
                for b in 0..o.len() {
                    if crosses(q[a], q[(a + 1) % n], o[b], o[(b + 1) % o.len()]) {
                        return Some([i, a, h, b]);
                    }
                }
            }
        }
    }
    None
}

/// Smoothing moves a crack point off its spring's midpoint along the crack; on a distorted
/// irregular mesh, at a sharp turn or near the open border, the unclamped offset moved points
/// past a neighbouring piece of the same ring, and the ring crossed itself (its triangles then
/// add up to more than its area). These runs, found by drawing the property tests' parameters
/// (`tests/properties.rs`), each crossed one of their rings before the offsets were kept in
/// their springs' regions; now no ring crosses itself or a hole in it.
#[test]
fn smoothed_cell_rings_do_not_cross_themselves() {
    use hibi_core::mud::{Boundary, Drive};
    let base = MudParams { boundary: Boundary::Open, topology: Topology::Irregular, ..MudParams::default() };
    let cases = [
        // Irregular, explicit, open, shrink: ring 15's edges 5 and 8 crossed.
        MudParams {
            solver: Solver::Explicit,
            drive: Drive::Shrink,
            columns: 12,
            rows: 12,
            seed: 148545713348754418,
            layer_thickness: 0.5467682,
            element_size: 0.82277834,
            long_step: 1.0,
            short_step: 0.001,
            shrink_ratio: 0.99529356,
            displacement_tolerance: 0.00016870038,
            damping_factor: 35.397106,
            density: 1.990847,
            young_modulus: 1487811.8,
            shear_modulus: 273080.47,
            break_stretch_mean: 1.0960561,
            break_stretch_spread: 0.041897714,
            break_stretch_size_exponent: 0.57749873,
            anisotropy_direction: -1.0018792,
            anisotropy_ratio: 2.9511204,
            stiffness_anisotropy_ratio: 1.419309,
            target_shrink: 0.05,
            target_crack_density: 0.0,
            ..base
        },
        // Irregular, quasi-static, open, growth: ring 18's edges 1 and 28 crossed.
        MudParams {
            solver: Solver::QuasiStatic,
            drive: Drive::Growth,
            columns: 12,
            rows: 18,
            seed: 5876250752890210833,
            layer_thickness: 0.76409435,
            element_size: 1.925241,
            long_step: 1.9925058,
            short_step: 0.0018474383,
            shrink_ratio: 0.9943324,
            displacement_tolerance: 9.96202e-5,
            damping_factor: 35.817398,
            density: 1.7212682,
            young_modulus: 2730146.5,
            shear_modulus: 453971.9,
            break_stretch_mean: 1.0392312,
            break_stretch_spread: 0.0454157,
            break_stretch_size_exponent: 0.81817824,
            anisotropy_direction: -1.5758313,
            anisotropy_ratio: 1.3887274,
            stiffness_anisotropy_ratio: 2.2361126,
            target_shrink: 0.03939564,
            target_crack_density: 2.038333,
            ..base
        },
    ];
    for p in &cases {
        let (_, rings, points, _) = cells(p);
        assert!(rings.len() > 10, "{p:?}: {} rings", rings.len());
        assert_eq!(ring_crossing(&rings, &points), None, "{p:?}");
    }
}

/// Steps `params` on backend `S` in calls of a million units of work until the run finishes
/// or has done `limit` units; returns where it stands.
fn run_within<S: Scalar>(params: &MudParams, limit: u64) -> hibi_core::mud::MudProgress {
    let memory = params.memory().expect("valid parameters");
    let (mut scalars, mut words) = (vec![S::ZERO; memory.scalars], vec![0u32; memory.words]);
    let mut mud = Mud::new(params, MudBuffers { scalars: &mut scalars, words: &mut words }).expect("memory suffices");
    let mut progress = mud.progress();
    while !progress.finished && progress.work < limit {
        progress = mud.step(1_000_000).unwrap();
    }
    progress
}

/// The explicit solver's run ends on the Q16.16 backend, within twice the work of the f32 run
/// of the same parameters, and breaks as many springs within 20 %. At the paper's values a
/// Q16.16 lattice comes to rest with forces of up to 37 units of the format left (20×20
/// hexagonal, at 1.49 % shrink) against a force tolerance δF of one unit: no node moves by a
/// unit in a short step (F·τ/c < 1), so every short step repeats the last, and the run ends
/// only because a short step that moves nothing and breaks nothing counts as settled. The
/// same happens in f32 when an open plate is pulled far (growth to the end with springs
/// that break only at three times their length: displacements of tens of elements, whose
/// f32 steps are coarser than a short step's move), and there both backends end too.
#[test]
fn explicit_runs_end_on_every_backend() {
    let explicit = MudParams { solver: Solver::Explicit, ..params(20) };
    let cases = [
        ("hexagonal periodic shrink", explicit),
        (
            "square open growth",
            MudParams {
                topology: Topology::Square,
                boundary: Boundary::Open,
                drive: hibi_core::mud::Drive::Growth,
                rows: 16,
                ..explicit
            },
        ),
        ("irregular periodic shrink", MudParams { topology: Topology::Irregular, ..explicit }),
    ];
    for (name, p) in cases {
        let float = run_within::<f32>(&p, u64::MAX);
        let fixed = run_within::<Q16>(&p, 2 * float.work);
        println!("{name}: f32 {float:?}\n{name}: Q16 {fixed:?}");
        assert!(fixed.finished, "{name}: {fixed:?}");
        assert!(
            within(float.broken_springs as f32, fixed.broken_springs as f32, 0.2),
            "{name}: {float:?} vs {fixed:?}"
        );
    }
    let pulled = MudParams {
        boundary: Boundary::Open,
        drive: hibi_core::mud::Drive::Growth,
        break_stretch_mean: 3.0,
        shrink_ratio: 0.99,
        target_shrink: 0.0,
        ..params(10)
    };
    let pulled = MudParams { solver: Solver::Explicit, ..pulled };
    for (backend, end) in
        [("f32", run_within::<f32>(&pulled, 400_000_000)), ("Q16", run_within::<Q16>(&pulled, 400_000_000))]
    {
        println!("pulled {backend}: {end:?}");
        assert!(end.finished && end.shrink >= 100.0, "{backend}: {end:?}");
    }
}

/// The quasi-static relaxation ends when the displacement tolerance δx is below what the
/// backend resolves: at the smallest δx the validation accepts (k_min·δx/W = 1e-6, δx/W a
/// third of a unit of Q16.16) on an open plate shrunk to the end, the Q16.16 run ends within
/// twice the f32 run's work, breaking as many springs as the f32 run (its tolerance is at
/// least a few units of its resolution, so rounding is not relaxed back and forth between
/// neighbours).
#[test]
fn quasi_static_runs_end_with_a_tolerance_below_the_backends_resolution() {
    let p = MudParams { boundary: Boundary::Open, target_shrink: 0.0, displacement_tolerance: 5.8e-6, ..params(10) };
    assert!(p.memory().is_ok());
    let float = run_within::<f32>(&p, u64::MAX);
    let fixed = run_within::<Q16>(&p, 2 * float.work);
    println!("f32 {float:?}\nQ16 {fixed:?}");
    assert!(float.finished && fixed.finished, "{fixed:?}");
    assert_eq!(fixed.broken_springs, float.broken_springs);
}

/// Length-weighted crack orientations of the network, in 12 bins over 180°, each as a
/// share of the flat distribution (1 everywhere when flat).
fn orientation_bins(n: &Network) -> [f64; 12] {
    let mut bins = [0.0f64; 12];
    for e in &n.edges {
        for w in n.polyline(e).windows(2) {
            let (dx, dy) = (f64::from(w[1].at[0] - w[0].at[0]), f64::from(w[1].at[1] - w[0].at[1]));
            let angle = dy.atan2(dx).rem_euclid(std::f64::consts::PI);
            bins[((angle / std::f64::consts::PI * 12.0) as usize).min(11)] += dx.hypot(dy);
        }
    }
    let total: f64 = bins.iter().sum();
    bins.map(|b| b / total * 12.0)
}

#[test]
fn the_irregular_lattice_cracks_in_every_direction() {
    let mut shares = [[0.0f64; 12]; 2];
    for (t, topology) in [Topology::Hexagonal, Topology::Irregular].into_iter().enumerate() {
        for seed in 1..=8 {
            let bins = orientation_bins(&network(&MudParams { seed, topology, ..MudParams::default() }));
            for (share, b) in shares[t].iter_mut().zip(bins) {
                *share += b / 8.0;
            }
        }
        let (low, high) = shares[t].iter().fold((f64::MAX, 0.0f64), |(a, b), &s| (a.min(s), b.max(s)));
        println!("{topology:?}: crack length per 15° bin over flat {low:.2}..{high:.2}: {:.2?}", shares[t]);
    }
    // The irregular lattice: every bin within ±20 % of flat.
    assert!(shares[1].iter().all(|s| (s - 1.0).abs() <= 0.2), "{:?}", shares[1]);
    // The hexagonal lattice's cracks still lean to its three directions, smoothed along the
    // cracks as they are (bins of about ±28 %; ±50 % through the midpoints alone): its
    // spread of bins is over twice the irregular lattice's.
    let spread = |s: &[f64; 12]| s.iter().fold(0.0f64, |m, &v| m.max((v - 1.0).abs()));
    assert!(spread(&shares[0]) > 2.0 * spread(&shares[1]), "{shares:?}");
}

#[test]
fn open_plates_have_cells_bounded_by_the_border() {
    for topology in [Topology::Hexagonal, Topology::Square] {
        let p = MudParams { boundary: Boundary::Open, topology, target_shrink: 0.03, ..params(48) };
        let (counts, rings, _, [w, h]) = cells(&p);
        let total: f64 = rings.iter().map(|r| r.area).sum();
        let outer = rings.iter().filter(|r| r.area > 0.0).count();
        println!("{topology:?} open: {outer} cells; area {total:.1} of the undeformed {:.1}", w * h);
        assert_eq!(counts.wrapping, 0);
        assert!(outer > 1, "{topology:?}");
        // The surface shrank onto the deep layer: a little less than the undeformed plate.
        let mesh = match topology {
            Topology::Hexagonal => (w - 0.5) * (h - h / 48.0),
            Topology::Square => (w - 1.0) * (h - 1.0),
            Topology::Irregular => unreachable!(),
        };
        assert!(total < f64::from(mesh) && total > 0.95 * f64::from(mesh), "{topology:?}: {total} vs {mesh}");
    }
}

#[test]
fn statistics_are_those_of_the_network_and_its_cells() {
    let p = MudParams { seed: 3, ..params(96) };
    let memory = p.memory().unwrap();
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let mut mud = Mud::new(&p, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
    mud.run().unwrap();
    let stats = mud.statistics();
    let n = network(&p);
    let (counts, rings, _, [w, h]) = cells(&p);
    let outer: Vec<f64> = rings.iter().filter(|r| r.area > 0.0).map(|r| r.area).collect();
    assert_eq!(stats.cells as usize, outer.len() + counts.wrapping);
    assert!((stats.mean_cell_area - w * h / outer.len() as f32).abs() < 1e-3 * stats.mean_cell_area);
    let mean = outer.iter().sum::<f64>() / outer.len() as f64;
    let spread = (outer.iter().map(|a| (a - mean) * (a - mean)).sum::<f64>() / outer.len() as f64).sqrt();
    assert!((f64::from(stats.cell_area_spread) - spread).abs() < 1e-3 * spread, "{stats:?} vs {spread}");
    assert_eq!(stats.junctions as usize, n.vertices.iter().filter(|v| v.degree >= 3).count());
    assert_eq!(stats.dead_ends as usize, n.vertices.iter().filter(|v| v.degree == 1 && v.on_border == 0).count());
    let length: f32 = n.edges.iter().map(|e| n.length(e)).sum();
    assert!((stats.crack_density - length / (w * h)).abs() < 1e-3 * stats.crack_density, "{stats:?} vs {length}");
    assert!(stats.t_junctions > 0 && stats.t_junctions <= stats.junctions);
    println!("{stats:?}");
}

/// Labels the 8-connected pieces of `on` pixels on a wrapping `size`² raster; returns each
/// piece's pixel count.
fn pieces_8_connected(on: &[bool], size: usize) -> Vec<usize> {
    let mut seen = vec![false; on.len()];
    let mut pieces = Vec::new();
    let mut stack = Vec::new();
    for start in 0..on.len() {
        if !on[start] || seen[start] {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        let mut count = 0;
        while let Some(i) = stack.pop() {
            count += 1;
            let (x, y) = ((i % size) as isize, (i / size) as isize);
            for (dx, dy) in [(-1, -1), (0, -1), (1, -1), (-1, 0), (1, 0), (-1, 1), (0, 1), (1, 1)] {
                let (nx, ny) = ((x + dx).rem_euclid(size as isize), (y + dy).rem_euclid(size as isize));
                let j = ny as usize * size + nx as usize;
                if on[j] && !seen[j] {
                    seen[j] = true;
                    stack.push(j);
                }
            }
        }
        pieces.push(count);
    }
    pieces
}

#[test]
fn the_default_mask_shows_thin_connected_cracks() {
    // What `hibi mud --layer mask --size 512` draws: the default run, 4 px per spacing, the
    // CLI's default narrowest stroke (0.8 px rounds up to 1 px).
    let p = MudParams::default();
    let memory = p.memory().unwrap();
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let mut mud = Mud::new(&p, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
    mud.run().unwrap();
    let render = MudRender { width: 512, height: 512, ..MudRender::default() };
    let mut mask = vec![0u8; 512 * 512];
    mud.render(&render, MudLayers { mask: Some(&mut mask), ..Default::default() }).unwrap();
    let on: Vec<bool> = mask.iter().map(|&v| v >= 128).collect();
    let cracked = on.iter().filter(|&&c| c).count();
    let pieces = pieces_8_connected(&on, 512);
    let largest = pieces.iter().copied().max().unwrap_or(0);
    let share = cracked as f32 / on.len() as f32;
    println!(
        "crack pixels {:.1} %, largest 8-connected piece {:.1} %",
        100.0 * share,
        100.0 * largest as f32 / cracked as f32
    );
    assert!(share <= 0.12, "{share}");
    assert!(largest as f32 >= 0.95 * cracked as f32, "{largest} of {cracked}");
}

/// Paper Fig. 6 b: square elements carry no in-plane shear, and their network is a maze of
/// short axis-aligned cracks meeting at right angles: nearly every junction is a T (a crack
/// runs on straight, another meets it square), the network is fine (more crack length per
/// area than the hexagonal lattice's), and no crack ends inside a cell. The hexagonal
/// lattice's junctions are T's less often. (Its cells are about as large: 18.1 cm² for
/// fig6b, 16.9 for fig6a at the default 2.3 % shrink, seed 1.)
#[test]
fn the_square_lattice_gives_a_maze_of_short_cracks_meeting_square() {
    let stats = |name: &str| {
        let p = hibi_core::mud::preset(name).expect("a preset");
        let memory = p.memory().unwrap();
        let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
        let mut mud = Mud::new(&p, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
        mud.run().unwrap();
        mud.statistics()
    };
    let (square, hexagonal) = (stats("fig6b"), stats("fig6a"));
    println!("fig6b {square:?}\nfig6a {hexagonal:?}");
    let t_share = |s: &hibi_core::mud::CrackStatistics| s.t_junctions as f32 / s.junctions as f32;
    assert!(t_share(&square) > 0.75 && square.mean_widest_junction_angle > 170.0, "{square:?}");
    assert!(t_share(&hexagonal) < t_share(&square) - 0.05, "{hexagonal:?}");
    assert!(square.dead_ends as f32 <= 0.05 * square.junctions as f32, "{square:?}");
    assert!(square.crack_density > hexagonal.crack_density, "{square:?} vs {hexagonal:?}");
}

#[test]
fn network_and_cells_refuse_short_buffers_and_write_nothing() {
    use hibi_core::mud::{MudError, NetworkEdge, NetworkPoint, NetworkVertex};
    use hibi_core::polygon::Ring;
    let p = params(48);
    let memory = p.memory().unwrap();
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let mut mud = Mud::new(&p, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
    mud.run().unwrap();
    let n = mud.network_counts();
    let sentinel_vertex = NetworkVertex { degree: 77, ..Default::default() };
    let sentinel_edge = NetworkEdge { from: 77, ..Default::default() };
    let sentinel_point = NetworkPoint { width: 77.0, ..Default::default() };
    let (mut v, mut e, mut q) =
        (vec![sentinel_vertex; n.vertices], vec![sentinel_edge; n.edges], vec![sentinel_point; n.points]);
    for (short, needed) in [(0, n.vertices), (1, n.edges), (2, n.points)] {
        let result = match short {
            0 => mud.network(&mut v[..n.vertices - 1], &mut e, &mut q),
            1 => mud.network(&mut v, &mut e[..n.edges - 1], &mut q),
            _ => mud.network(&mut v, &mut e, &mut q[..n.points - 1]),
        };
        assert_eq!(result, Err(MudError::BufferTooSmall { needed }));
        assert!(v.iter().all(|x| *x == sentinel_vertex) && e.iter().all(|x| *x == sentinel_edge));
        assert!(q.iter().all(|x| *x == sentinel_point));
    }
    assert_eq!(mud.network(&mut v, &mut e, &mut q), Ok(n));
    let c = mud.cell_counts();
    let sentinel_ring = Ring { hole_of: 77, ..Default::default() };
    let (mut rings, mut points) = (vec![sentinel_ring; c.rings], vec![[77.0f32; 2]; c.points]);
    assert_eq!(mud.cells(&mut rings, &mut points[..c.points - 1]), Err(MudError::BufferTooSmall { needed: c.points }));
    assert!(rings.iter().all(|r| *r == sentinel_ring) && points.iter().all(|p| *p == [77.0; 2]));
    assert_eq!(mud.cells(&mut rings, &mut points), Ok(c));
}

/// The explicit solver's run, bit for bit, on every lattice and both drives and backends:
/// every spring's break time and the traced segments, hashed (the same under any frame
/// budget: stopping anywhere in a short step changes no bit).
#[test]
fn golden_explicit_runs() {
    fn hash<S: Scalar>(name: &str, params: &MudParams) -> u64 {
        let (_, segments, _) = run::<S>(params);
        let memory = params.memory().unwrap();
        let (mut scalars, mut words) = (vec![S::ZERO; memory.scalars], vec![0u32; memory.words]);
        let mut mud = Mud::new(params, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
        mud.run().unwrap();
        let springs = mud.lattice().spring_count();
        let times: Vec<u8> = (0..springs)
            .flat_map(|s| mud.spring_break_time(s).map_or(u32::MAX, f32::to_bits).to_le_bytes())
            .chain(segments.to_le_bytes())
            .collect();
        let h = fnv1a64(&times);
        println!("{name}: {h} ({} broken)", mud.progress().broken_springs);
        h
    }
    use hibi_core::mud::Drive;
    let explicit = MudParams { solver: Solver::Explicit, ..params(20) };
    let square = MudParams { topology: Topology::Square, ..explicit };
    let irregular = MudParams { topology: Topology::Irregular, ..explicit };
    let (open, growth) = (Boundary::Open, Drive::Growth);
    let cases = [
        hash::<f32>("hex periodic shrink f32", &explicit),
        hash::<f32>("hex open shrink f32", &MudParams { boundary: open, ..explicit }),
        hash::<f32>("hex open growth f32", &MudParams { boundary: open, drive: growth, ..explicit }),
        hash::<f32>("square open growth f32", &MudParams { boundary: open, drive: growth, rows: 16, ..square }),
        hash::<f32>("square periodic shrink f32", &MudParams { rows: 18, ..square }),
        hash::<f32>("irregular periodic shrink f32", &irregular),
        hash::<f32>("irregular open growth f32", &MudParams { boundary: open, drive: growth, ..irregular }),
    ];
    let expected: [u64; 7] = [
        12454092001312085556,
        2711182118146359711,
        17684844049900681505,
        1063005523725258606,
        12905387523669546347,
        2654304470968482606,
        16330958032564823092,
    ];
    assert_eq!(cases, expected);
}

/// The environment variable that makes
/// [`creating_a_run_takes_the_same_instructions_whatever_the_lattice_size`], run under
/// Callgrind by itself, create one case (`topology:size`) instead of measuring them all.
const CREATE_CASE: &str = "HIBI_MUD_CREATE_CASE";

/// Creates a run; the only function Callgrind counts in
/// [`creating_a_run_takes_the_same_instructions_whatever_the_lattice_size`] (found by its
/// unmangled name).
#[unsafe(no_mangle)]
#[inline(never)]
fn hibi_test_mud_new<'a>(p: &MudParams, buffers: MudBuffers<'a, f32>) -> Mud<'a, f32> {
    Mud::new(p, buffers).expect("memory suffices")
}

/// What `Mud::new` costs, in instructions (Callgrind, so the same on any machine), does not
/// grow with the lattice: a 1024² lattice takes at most 1.1 times the instructions of a 64²
/// one, regular and irregular, with either solver (the rest of the setup is done by the first
/// steps, within their budgets). Each case is created under Callgrind by this test binary
/// itself (the case named by [`CREATE_CASE`]), counting `hibi_test_mud_new` alone.
#[test]
fn creating_a_run_takes_the_same_instructions_whatever_the_lattice_size() {
    let case_params = |case: &str| {
        let (topology, rest) = case.split_once(':').expect("topology:solver:size");
        let (solver, size) = rest.split_once(':').expect("solver:size");
        let topology = if topology == "irregular" { Topology::Irregular } else { Topology::Hexagonal };
        let solver = if solver == "explicit" { Solver::Explicit } else { Solver::QuasiStatic };
        let size = size.parse().expect("a size");
        MudParams { topology, solver, columns: size, rows: size, ..MudParams::default() }
    };
    if let Ok(case) = std::env::var(CREATE_CASE) {
        // Under Callgrind: create the case and report what it holds.
        let p = case_params(&case);
        let mut memory = p.memory().expect("valid parameters").allocate();
        let mud = hibi_test_mud_new(&p, memory.buffers());
        println!("\nmud created {:?}", mud.progress());
        return;
    }
    for topology in ["hexagonal", "irregular"] {
        for solver in ["explicit", "quasi-static"] {
            let mut counts = Vec::new();
            for size in [64, 1024] {
                let case = format!("{topology}:{solver}:{size}");
                let (stdout, instructions) = hibi_tests::callgrind_this_test(
                    "creating_a_run_takes_the_same_instructions_whatever_the_lattice_size",
                    "hibi_test_mud_new",
                    (CREATE_CASE, &case),
                );
                let created = stdout.lines().find_map(|l| l.strip_prefix("mud created ")).map(str::to_owned);
                let created = created.unwrap_or_else(|| panic!("{case}: no run reported in\n{stdout}"));
                println!("{case}: {instructions} instructions; {created}");
                counts.push((instructions, created));
            }
            assert_eq!(counts[0].1, counts[1].1, "{topology} {solver}: the same progress");
            let (small, large) = (counts[0].0 as f64, counts[1].0 as f64);
            assert!(large <= 1.1 * small, "{topology} {solver}: {large} instructions at 1024², {small} at 64²");
        }
    }
}

/// Everything a run leaves, to compare runs bit for bit: progress, break times, segments,
/// network, cells, statistics.
#[derive(Clone, Debug, PartialEq)]
struct Readout {
    /// The progress but its work.
    progress: String,
    work: u64,
    break_times: Vec<Option<u32>>,
    segments: Vec<[u32; 8]>,
    network: String,
    cells: String,
    statistics: String,
}

fn readout(mud: &Mud<'_, f32>) -> Readout {
    let counts = mud.network_counts();
    let mut v = vec![Default::default(); counts.vertices];
    let mut e = vec![Default::default(); counts.edges];
    let mut q = vec![Default::default(); counts.points];
    mud.network(&mut v, &mut e, &mut q).expect("sized");
    let cells = mud.cell_counts();
    let (mut rings, mut points) = (vec![Default::default(); cells.rings], vec![[0.0f32; 2]; cells.points]);
    mud.cells(&mut rings, &mut points).expect("sized");
    let mut segments = Vec::new();
    mud.for_each_segment(|s| {
        let v = [s.start, s.end, s.width, s.time].concat();
        segments.push(std::array::from_fn(|i| v[i].to_bits()));
    });
    Readout {
        progress: format!("{:?}", MudProgress { work: 0, ..mud.progress() }),
        work: mud.progress().work,
        break_times: (0..mud.lattice().spring_count()).map(|s| mud.spring_break_time(s).map(f32::to_bits)).collect(),
        segments,
        network: format!("{v:?} {e:?} {q:?}"),
        cells: format!("{cells:?} {rings:?} {points:?}"),
        statistics: format!("{:?}", mud.statistics()),
    }
}

/// The cases of the budget tests: square, hexagonal and irregular lattices with both solvers,
/// open and periodic edges, shrink and growth, small enough to step one unit at a time.
fn budget_cases() -> Vec<MudParams> {
    let small = MudParams { columns: 10, rows: 8, target_shrink: 0.03, ..MudParams::default() };
    let mut cases = Vec::new();
    for (i, topology) in [Topology::Square, Topology::Hexagonal, Topology::Irregular].into_iter().enumerate() {
        for (j, solver) in [Solver::Explicit, Solver::QuasiStatic].into_iter().enumerate() {
            let boundary = if (i + j) % 2 == 0 { Boundary::Open } else { Boundary::Periodic };
            let drive = if j == 0 && i == 1 { hibi_core::mud::Drive::Growth } else { hibi_core::mud::Drive::Shrink };
            cases.push(MudParams { topology, solver, boundary, drive, ..small });
        }
    }
    cases
}

/// Runs `p` in `scalars` and `words` with `budget` per call (`None`: one `run()`), asserting
/// that no call does more than max(budget, 1) − 1 + one piece (the setup's, a row's springs
/// and their rescan, a node's springs, or the tracing's), and that while nothing has broken
/// the outputs show no crack. Returns the readout.
fn run_budgeted(p: &MudParams, scalars: &mut [f32], words: &mut [u32], budget: Option<u64>) -> Readout {
    let mut mud = Mud::new(p, MudBuffers { scalars, words }).expect("memory suffices");
    let uncracked = readout(&mud);
    assert!(uncracked.segments.is_empty() && uncracked.break_times.iter().all(Option::is_none), "{p:?}");
    let piece = match p.solver {
        Solver::Explicit => 2 * u64::from(p.columns),
        Solver::QuasiStatic => 16,
    }
    .max(hibi_core::mud::TRACE_PIECE)
    .max(hibi_core::mud::SETUP_PIECE);
    match budget {
        None => {
            mud.run().expect("a stable run");
        }
        Some(budget) => loop {
            let before = mud.progress().work;
            let progress = mud.step(budget).expect("a stable run");
            let done = progress.work - before;
            let bound = budget.max(1) - 1 + piece;
            assert!(done <= bound, "{p:?}: budget {budget}: {done} > {bound}");
            // (Past the setup and its first units, at most a few thousand here.)
            if progress.work < 4000 && progress.broken_springs == 0 && !mud.is_tracing() {
                let now = readout(&mud);
                // No crack (the cells: none while the setup is under way, as while a trace is;
                // an open plate's border once it is done).
                assert_eq!((&now.segments, &now.network), (&uncracked.segments, &uncracked.network), "{p:?}");
            }
            if progress.finished {
                break;
            }
        },
    }
    readout(&mud)
}

/// Frame budgets, the setup included: every budget in {0, 1, 7, 100} gives the same run, bit
/// for bit, in every element of the buffers (displacements, break stretches, break times, the
/// mesh, the solver's arrays, the network's two copies) and every output and its work, on every
/// lattice with both solvers; no call does more than max(budget, 1) − 1 + one piece. One
/// unbounded call (`run`) ends with the same outputs and the same physics in its buffers, in
/// less work: it makes no live trace.
#[test]
fn every_budget_sets_up_and_runs_the_run_of_one_call() {
    for p in budget_cases() {
        let m = p.memory().expect("valid parameters");
        let (mut scalars, mut words) = (vec![0.0f32; m.scalars], vec![0u32; m.words]);
        let stepped = run_budgeted(&p, &mut scalars, &mut words, Some(1));
        assert!(!stepped.segments.is_empty(), "{p:?}: nothing broke");
        for budget in [0, 7, 100] {
            let (mut s, mut w) = (vec![0.0f32; m.scalars], vec![0u32; m.words]);
            let run = run_budgeted(&p, &mut s, &mut w, Some(budget));
            assert!(run == stepped, "{p:?}: budget {budget} changed the outputs");
            let same_scalars = s.iter().zip(&scalars).all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same_scalars && w == words, "{p:?}: budget {budget} changed the buffers");
        }
        let (mut s, mut w) = (vec![0.0f32; m.scalars], vec![0u32; m.words]);
        let whole = run_budgeted(&p, &mut s, &mut w, None);
        assert!(whole == Readout { work: whole.work, ..stepped.clone() }, "{p:?}: run() changed the outputs");
        assert!(whole.work < stepped.work, "{p:?}: run() did {} units, stepped {}", whole.work, stepped.work);
        let same_scalars = s.iter().zip(&scalars).all(|(a, b)| a.to_bits() == b.to_bits());
        assert!(same_scalars, "{p:?}: run() changed the physics");
    }
}

/// The buffers may hold any bytes: a run over buffers filled with a byte pattern (0xa5, 0xff)
/// gives the outputs and the work of one over zeroed buffers, stepped or in one call.
#[test]
fn a_run_over_buffers_of_any_bytes_is_the_run_over_zeroed_ones() {
    for p in budget_cases() {
        let m = p.memory().expect("valid parameters");
        for budget in [None, Some(7)] {
            let (mut scalars, mut words) = (vec![0.0f32; m.scalars], vec![0u32; m.words]);
            let zeroed = run_budgeted(&p, &mut scalars, &mut words, budget);
            for byte in [0xa5u8, 0xff] {
                let word = u32::from_ne_bytes([byte; 4]);
                let (mut s, mut w) = (vec![f32::from_bits(word); m.scalars], vec![word; m.words]);
                let run = run_budgeted(&p, &mut s, &mut w, budget);
                assert!(run == zeroed, "{p:?}: bytes {byte:#x}, budget {budget:?} changed the run");
            }
        }
    }
}

/// An irregular lattice's explicit run is tested for stability on its mesh, which the first
/// steps build: `Mud::new` accepts a short step the mesh refuses, the step that finds the
/// failing node returns `ShortStepStability`, and so does every later call; the outputs stay
/// those of the uncracked plate.
#[test]
fn an_unstable_irregular_explicit_run_is_refused_by_its_setup_steps() {
    use hibi_core::mud::{MudError, MudParamError};
    let p = MudParams {
        topology: Topology::Irregular,
        solver: Solver::Explicit,
        boundary: Boundary::Open,
        columns: 12,
        rows: 12,
        short_step: 1.0,
        ..MudParams::default()
    };
    let m = p.memory().expect("the mesh is not built yet: accepted");
    let refused = Err(MudError::Param(MudParamError::ShortStepStability));
    for budget in [1, 100, u64::MAX] {
        let (mut s, mut w) = (vec![0.0f32; m.scalars], vec![0u32; m.words]);
        let mut mud = Mud::new(&p, MudBuffers { scalars: &mut s, words: &mut w }).expect("accepted");
        let uncracked = readout(&mud);
        let mut calls = 0;
        let found = loop {
            calls += 1;
            match mud.step(budget) {
                Ok(progress) => assert!(!progress.finished && progress.shrink == 0.0, "{progress:?}"),
                Err(e) => break Err(e),
            }
        };
        assert_eq!(found, refused, "budget {budget}");
        assert!(budget != 1 || calls > 1000, "budget 1: refused after {calls} calls, before the mesh was built?");
        assert_eq!(mud.step(budget), refused);
        assert_eq!(mud.run(), refused);
        let after = readout(&mud);
        assert_eq!(
            (&after.segments, &after.network, &after.cells),
            (&uncracked.segments, &uncracked.network, &uncracked.cells)
        );
        assert!(mud.lattice().mesh().is_some(), "the mesh was built");
    }
}

/// Mud live, as an engine shows it: a budgeted run renders every frame from the network it
/// shows, a whole trace of the springs broken a moment before. From the frame of the first
/// break (or the next) on, every frame shows cracks; the springs the network shows never fall;
/// no pixel of a frame's break-time raster is later than the run's time then; most of the
/// frames' cracked pixels (80 % or more) lie within a pixel of the finished run's break-time
/// raster cut at the frame's time (the rest: the network read at an earlier time, the surface
/// moved since); and
/// the last frame is the finished run's, bit for bit.
#[test]
fn a_budgeted_run_shows_its_cracks_as_they_break() {
    for (solver, size, budget) in [(Solver::QuasiStatic, 40, 20_000), (Solver::Explicit, 24, 1_000_000)] {
        let p = MudParams { columns: size, rows: size, seed: 11, solver, ..MudParams::default() };
        let render = MudRender::fit(p.extent(), 160);
        let pixels = (render.width * render.height) as usize;
        let memory = p.memory().unwrap();
        let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
        let mut finished = vec![0.0f32; pixels];
        {
            let mut mud = Mud::new(&p, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
            mud.run().unwrap();
            mud.render(&render, MudLayers { time: Some(&mut finished), ..MudLayers::default() }).unwrap();
        }
        let mut mud = Mud::new(&p, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
        let (mut mask, mut time) = (vec![0u8; pixels], vec![0.0f32; pixels]);
        let (mut frame, mut first_break, mut first_shown, mut shown, mut networks) = (0, None, None, 0, 0);
        let (mut least_near, mut near_total, mut cracked_total) = (1.0f32, 0usize, 0usize);
        let w = render.width as i64;
        loop {
            let progress = mud.step(budget).unwrap();
            mud.render(&render, MudLayers { mask: Some(&mut mask), time: Some(&mut time), ..MudLayers::default() })
                .unwrap();
            let cracked: Vec<usize> = (0..pixels).filter(|&i| mask[i] > 0).collect();
            if first_break.is_none() && progress.broken_springs > 0 {
                first_break = Some(frame);
            }
            if first_shown.is_none() && !cracked.is_empty() {
                first_shown = Some(frame);
            }
            assert!(first_shown.is_none() || !cracked.is_empty(), "{solver:?}: frame {frame} shows no crack");
            let now = mud.shown_broken_springs();
            assert!(now >= shown && now <= progress.broken_springs, "{solver:?}: frame {frame}: {now} after {shown}");
            networks += usize::from(now != shown);
            shown = now;
            let t = progress.time;
            let latest = time.iter().copied().filter(|v| v.is_finite()).fold(f32::NEG_INFINITY, f32::max);
            assert!(latest <= t, "{solver:?}: frame {frame} shows a crack at {latest}, later than {t}");
            let near = |i: usize| {
                let (x, y) = (i as i64 % w, i as i64 / w);
                (-1..=1).any(|dy| {
                    (-1..=1).any(|dx| {
                        let (x, y) = (x + dx, y + dy);
                        x >= 0 && y >= 0 && x < w && y < i64::from(render.height) && finished[(y * w + x) as usize] <= t
                    })
                })
            };
            if !cracked.is_empty() {
                let n = cracked.iter().filter(|&&i| near(i)).count();
                least_near = least_near.min(n as f32 / cracked.len() as f32);
                (near_total, cracked_total) = (near_total + n, cracked_total + cracked.len());
            }
            frame += 1;
            if progress.finished {
                break;
            }
        }
        let (first_break, first_shown) = (first_break.unwrap(), first_shown.unwrap());
        println!(
            "{solver:?} {size}²: {frame} frames, first break in {first_break}, cracks from {first_shown}, \
             {networks} networks; cracked pixels within 1 px of the finished run's raster cut then: \
             {:.3} of all frames', at least {least_near:.3} of one frame's",
            near_total as f32 / cracked_total as f32
        );
        assert!(
            first_shown <= first_break + 1,
            "{solver:?}: first break {first_break}, first crack shown {first_shown}"
        );
        assert!(networks >= 4, "{solver:?}: {networks} networks shown");
        assert!(near_total as f32 >= 0.8 * cracked_total as f32, "{solver:?}: {near_total} of {cracked_total}");
        assert!(time.iter().zip(&finished).all(|(a, b)| a.to_bits() == b.to_bits()), "{solver:?}: the last frame");
    }
}
