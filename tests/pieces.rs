//! Pieces for a physics engine (`hibi_core::polygon`): the triangles and convex pieces of
//! glass fragments and mud cells add up to each polygon's area (outer ring minus holes),
//! every triangle is counter-clockwise, every convex piece strictly convex with at most 8
//! points; rings with holes, holes touching the outer ring, slits, collinear and repeated
//! points; degenerate and crossing rings end with bounded work; bad rings are refused by
//! name, nothing written.
use hibi_core::glass::{Glass, GlassParams};
use hibi_core::mud::{Mud, MudBuffers, MudParams};
use hibi_core::polygon::{
    ConvexPiece, MAX_PIECE_POINTS, NOT_A_HOLE, PiecesError, Ring, RingError, Triangle, convex_pieces, piece_counts,
    pieces_scratch, triangulate,
};

fn twice_area(a: [f32; 2], b: [f32; 2], c: [f32; 2]) -> f64 {
    let f = |p: [f32; 2]| p.map(f64::from);
    let (a, b, c) = (f(a), f(b), f(c));
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// The pieces of `rings`, checked; returns the worst relative area error of any polygon over
/// triangles and pieces, and (polygons, triangles, pieces).
fn check(rings: &[Ring], points: &[[f32; 2]]) -> (f64, [usize; 3]) {
    let mut scratch = vec![0u32; pieces_scratch(rings, points).unwrap()];
    let counts = piece_counts(rings, points, &mut scratch).unwrap();
    let mut triangles = vec![Triangle::default(); counts.triangles];
    let mut pieces = vec![ConvexPiece::default(); counts.pieces];
    assert_eq!(triangulate(rings, points, &mut scratch, &mut triangles), Ok(counts.triangles));
    assert_eq!(convex_pieces(rings, points, &mut scratch, &mut pieces), Ok(counts.pieces));
    let mut by_tri = vec![0.0f64; rings.len()];
    let mut by_piece = vec![0.0f64; rings.len()];
    for t in &triangles {
        let [a, b, c] = t.points.map(|i| points[i as usize]);
        let area = twice_area(a, b, c);
        assert!(area > 0.0, "triangle {t:?} of area {area}");
        by_tri[t.ring as usize] += area / 2.0;
    }
    for p in &pieces {
        let n = p.point_count as usize;
        assert!((3..=MAX_PIECE_POINTS).contains(&n), "{p:?}");
        assert!(p.points[n..].iter().all(|&i| i == 0));
        let q: Vec<[f32; 2]> = p.points[..n].iter().map(|&i| points[i as usize]).collect();
        for j in 0..n {
            assert!(twice_area(q[j], q[(j + 1) % n], q[(j + 2) % n]) > 0.0, "not strictly convex: {q:?}");
            by_piece[p.ring as usize] += twice_area([0.0, 0.0], q[j], q[(j + 1) % n]) / 2.0;
        }
    }
    let mut worst = 0.0f64;
    let mut polygons = 0;
    for (i, ring) in rings.iter().enumerate() {
        if ring.hole_of != NOT_A_HOLE {
            assert!(by_tri[i] == 0.0);
            continue;
        }
        polygons += 1;
        let want: f64 = ring.area + rings.iter().filter(|h| h.hole_of as usize == i).map(|h| h.area).sum::<f64>();
        let scale = ring.area.abs().max(1e-30);
        worst = worst.max((by_tri[i] - want).abs() / scale).max((by_piece[i] - want).abs() / scale);
    }
    (worst, [polygons, counts.triangles, counts.pieces])
}

fn glass_fragments(params: &GlassParams) -> (Vec<Ring>, Vec<[f32; 2]>) {
    let m = params.memory().unwrap();
    let mut memory = m.allocate();
    let mut g = Glass::new(params, memory.buffers()).unwrap();
    while !g.step(100_000).finished {}
    let mut scratch = vec![0u32; m.scratch];
    let (r, p) = g.fragment_counts(&mut scratch).unwrap();
    let (mut rings, mut points) = (vec![Ring::default(); r], vec![[0.0f32; 2]; p]);
    g.fragments(&mut scratch, &mut rings, &mut points).unwrap();
    (rings, points)
}

fn mud_cells(params: &MudParams) -> (Vec<Ring>, Vec<[f32; 2]>) {
    let memory = params.memory().unwrap();
    let (mut scalars, mut words) = (vec![0.0f32; memory.scalars], vec![0u32; memory.words]);
    let mut mud = Mud::new(params, MudBuffers { scalars: &mut scalars, words: &mut words }).unwrap();
    while !mud.step(1_000_000).unwrap().finished {}
    let counts = mud.cell_counts();
    let (mut rings, mut points) = (vec![Ring::default(); counts.rings], vec![[0.0; 2]; counts.points]);
    mud.cells(&mut rings, &mut points).unwrap();
    (rings, points)
}

#[test]
fn glass_fragments_pieces_add_up_to_the_plate() {
    let mut totals = [0usize; 3];
    let mut worst = 0.0f64;
    for seed in 0..8u64 {
        let params = GlassParams { seed, ..GlassParams::default() };
        let (rings, points) = glass_fragments(&params);
        let (w, c) = check(&rings, &points);
        worst = worst.max(w);
        totals.iter_mut().zip(c).for_each(|(t, c)| *t += c);
    }
    println!("glass: 8 plates, {totals:?} polygons/triangles/pieces, worst relative area error {worst:e}");
    assert!(worst <= 1e-6, "{worst}");
}

/// Whatever the cracks so far: a plate's fragments at every stage of its growth.
#[test]
fn glass_pieces_add_up_while_the_plate_cracks() {
    let mut worst = 0.0f64;
    let mut stages = 0;
    for seed in [3u64, 11] {
        let params = GlassParams { seed, width: 300.0, height: 200.0, impact: [140.0, 90.0], ..GlassParams::default() };
        let m = params.memory().unwrap();
        let mut memory = m.allocate();
        let mut g = Glass::new(&params, memory.buffers()).unwrap();
        let mut scratch = vec![0u32; m.scratch];
        loop {
            let finished = g.step(3_000).finished;
            let (r, p) = g.fragment_counts(&mut scratch).unwrap();
            let (mut rings, mut points) = (vec![Ring::default(); r], vec![[0.0f32; 2]; p]);
            g.fragments(&mut scratch, &mut rings, &mut points).unwrap();
            let (w, _) = check(&rings, &points);
            worst = worst.max(w);
            stages += 1;
            if finished {
                break;
            }
        }
    }
    println!("glass while cracking: {stages} stages, worst relative area error {worst:e}");
    assert!(stages > 10 && worst <= 1e-6, "{stages} {worst}");
}

/// Impacts `FLT_MIN` from an edge or a corner put fragment points `FLT_MIN` apart (the hub
/// and the border point below it): every stage's fragments are still cut into pieces that
/// add up. (With rounded orientation tests, 16 of these 150 plates had a stage refused as
/// crossing.)
#[test]
fn glass_pieces_of_impacts_flt_min_from_the_edge_add_up() {
    let t = f32::MIN_POSITIVE;
    let (mut worst, mut stages) = (0.0f64, 0);
    for seed in (0..25u64).map(|k| k * 7919 + 1) {
        for (width, height) in [(131.0, 129.0), (160.0, 160.0)] {
            for impact in [[width / 2.0, t], [t, height / 2.0], [t, t]] {
                let params = GlassParams { seed, width, height, impact, ..GlassParams::default() };
                let m = params.memory().unwrap();
                let mut memory = m.allocate();
                let mut g = Glass::new(&params, memory.buffers()).unwrap();
                let mut scratch = vec![0u32; m.scratch];
                for _ in 0..10 {
                    let finished = g.step(10_000).finished;
                    let (r, p) = g.fragment_counts(&mut scratch).unwrap();
                    let (mut rings, mut points) = (vec![Ring::default(); r], vec![[0.0f32; 2]; p]);
                    g.fragments(&mut scratch, &mut rings, &mut points).unwrap();
                    worst = worst.max(check(&rings, &points).0);
                    stages += 1;
                    if finished {
                        break;
                    }
                }
            }
        }
    }
    println!("impacts FLT_MIN from the edge: {stages} stages, worst relative area error {worst:e}");
    assert!(worst <= 1e-6, "{worst}");
}

#[test]
fn mud_cells_pieces_add_up_to_the_cells() {
    let mut totals = [0usize; 3];
    let mut worst = 0.0f64;
    for seed in 1..5u64 {
        for periodic in [false, true] {
            let mut params = MudParams { seed, columns: 48, rows: 48, ..MudParams::default() };
            if periodic {
                params.boundary = hibi_core::mud::Boundary::Periodic;
            }
            let (rings, points) = mud_cells(&params);
            let (w, c) = check(&rings, &points);
            worst = worst.max(w);
            totals.iter_mut().zip(c).for_each(|(t, c)| *t += c);
        }
    }
    println!("mud: 8 runs, {totals:?} polygons/triangles/pieces, worst relative area error {worst:e}");
    assert!(worst <= 1e-6, "{worst}");
}

fn ring(first: u32, count: u32, area: f64, hole_of: u32) -> Ring {
    Ring { area, first_point: first, point_count: count, hole_of, reserved: 0 }
}

#[test]
fn holes_touching_rings_slits_collinear_and_repeated_points() {
    // A square with two square holes, one touching the outer ring at (10, 5) and another hole
    // at (4, 4); repeated and collinear points on the outer ring.
    let points = [
        [0.0, 0.0],
        [5.0, 0.0],
        [5.0, 0.0],
        [10.0, 0.0],
        [10.0, 5.0],
        [10.0, 10.0],
        [0.0, 10.0],
        [2.0, 2.0],
        [2.0, 4.0],
        [4.0, 4.0],
        [4.0, 2.0],
        [4.0, 4.0],
        [6.0, 6.0],
        [8.0, 5.0],
        [10.0, 5.0],
        [8.0, 4.0],
    ];
    let hole2 = twice_area([4.0, 4.0], [6.0, 6.0], [8.0, 5.0]) / 2.0
        + twice_area([4.0, 4.0], [8.0, 5.0], [10.0, 5.0]) / 2.0
        + twice_area([4.0, 4.0], [10.0, 5.0], [8.0, 4.0]) / 2.0;
    let rings = [ring(0, 7, 100.0, NOT_A_HOLE), ring(7, 4, -4.0, 0), ring(11, 5, hole2, 0)];
    let (worst, counts) = check(&rings, &points);
    assert!(worst <= 1e-12 && counts[0] == 1, "{worst} {counts:?}");
    // A slit: the ring walks (0,0)–(5,5) both ways; a clockwise outer ring is turned round.
    let slit = [[0.0, 0.0], [5.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0], [0.0, 0.0], [5.0, 5.0]];
    let (worst, _) = check(&[ring(0, 7, 100.0, NOT_A_HOLE)], &slit);
    assert!(worst <= 1e-12, "{worst}");
    let mut reversed = slit;
    reversed.reverse();
    let (worst, _) = check(&[ring(0, 7, 100.0, NOT_A_HOLE)], &reversed.map(|p| [p[0], p[1]]));
    assert!(worst <= 1e-12, "{worst}");
}

#[test]
fn degenerate_rings_end_with_counter_clockwise_pieces_and_crossing_rings_are_refused() {
    // All collinear, all one point, a tiny sliver, fewer than 3 points.
    let cases: [&[[f32; 2]]; 4] = [
        &[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]],
        &[[1.0, 1.0], [1.0, 1.0], [1.0, 1.0]],
        &[[0.0, 0.0], [1e6, 0.0], [1e6, 1e-6], [0.0, 2e-6]],
        &[[0.0, 0.0], [1.0, 0.0]],
    ];
    for points in cases {
        let rings = [ring(0, points.len() as u32, 1.0, NOT_A_HOLE)];
        let mut scratch = vec![0u32; pieces_scratch(&rings, points).unwrap()];
        let mut triangles = vec![Triangle::default(); points.len()];
        let n = triangulate(&rings, points, &mut scratch, &mut triangles).unwrap();
        for t in &triangles[..n] {
            let [a, b, c] = t.points.map(|i| points[i as usize]);
            assert!(twice_area(a, b, c) > 0.0);
        }
        let mut pieces = vec![ConvexPiece::default(); points.len()];
        let k = convex_pieces(&rings, points, &mut scratch, &mut pieces).unwrap();
        assert!(k <= n);
    }
    // A bow tie, a figure of eight, and a square with a hole crossing its side: no pieces
    // cover a polygon whose rings cross, so it is refused by its outer ring's index, and
    // nothing is written.
    let square = [[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]];
    let cases: [(&[[f32; 2]], Vec<Ring>); 3] = [
        (&[[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]], vec![ring(0, 4, 0.0, NOT_A_HOLE)]),
        (
            &[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, -1.0], [0.5, -1.0]],
            vec![ring(0, 6, 0.5, NOT_A_HOLE)],
        ),
        (
            &[square[0], square[1], square[2], square[3], [3.0, 1.0], [3.0, 3.0], [5.0, 3.0], [5.0, 1.0]],
            vec![ring(0, 4, 16.0, NOT_A_HOLE), ring(0, 4, 16.0, NOT_A_HOLE), ring(4, 4, -4.0, 1)],
        ),
    ];
    for (points, rings) in &cases {
        let want = Err(PiecesError::Ring { ring: rings.len().saturating_sub(2).min(1), error: RingError::Crosses });
        let mut scratch = vec![7u32; pieces_scratch(rings, points).unwrap()];
        assert_eq!(piece_counts(rings, points, &mut scratch).map(|_| ()), want, "{points:?}");
        let mut triangles = [Triangle { ring: 9, points: [9; 3] }; 16];
        assert_eq!(triangulate(rings, points, &mut scratch, &mut triangles).map(|_| ()), want);
        let mut pieces = [ConvexPiece { ring: 9, ..ConvexPiece::default() }; 16];
        assert_eq!(convex_pieces(rings, points, &mut scratch, &mut pieces).map(|_| ()), want);
        assert!(triangles.iter().all(|t| t.ring == 9) && pieces.iter().all(|p| p.ring == 9), "nothing written");
    }
}

#[test]
fn bad_rings_are_refused_by_name_and_nothing_is_written() {
    let points = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [f32::NAN, 0.5]];
    let cases = [
        (vec![ring(0, 3, 0.5, NOT_A_HOLE), ring(2, 3, -0.1, 0)], 1, RingError::Points),
        (vec![ring(0, 3, 0.5, NOT_A_HOLE), ring(0, 3, -0.5, 1)], 1, RingError::HoleOf),
        (vec![ring(0, 3, 0.5, NOT_A_HOLE), ring(0, 3, -0.5, 2), ring(0, 3, -0.5, 0)], 1, RingError::HoleOf),
        (vec![ring(1, 3, 0.5, NOT_A_HOLE)], 0, RingError::NotFinite),
    ];
    for (rings, at, error) in &cases {
        let want = Err(PiecesError::Ring { ring: *at, error: *error });
        assert_eq!(pieces_scratch(rings, &points).map(|_| ()), want);
        let mut scratch = vec![7u32; 64];
        let mut triangles = [Triangle { ring: 9, points: [9; 3] }; 4];
        assert_eq!(triangulate(rings, &points, &mut scratch, &mut triangles).map(|_| ()), want);
        assert!(triangles.iter().all(|t| t.ring == 9) && scratch.iter().all(|&w| w == 7));
    }
    // A hole of a ring past the buffer (mud's hole in a wrapping cell) makes no pieces.
    let rings = [ring(0, 3, 0.5, u32::MAX - 1)];
    let mut scratch = vec![0u32; pieces_scratch(&rings, &points).unwrap()];
    assert_eq!(piece_counts(&rings, &points, &mut scratch).map(|c| c.triangles), Ok(0));
    // Short scratch and short output.
    let rings = [ring(0, 3, 0.5, NOT_A_HOLE)];
    let needed = pieces_scratch(&rings, &points).unwrap();
    let mut scratch = vec![0u32; needed - 1];
    assert_eq!(
        triangulate(&rings, &points, &mut scratch, &mut [Triangle::default(); 1]),
        Err(PiecesError::ScratchTooSmall { needed })
    );
    let mut scratch = vec![0u32; needed];
    let mut none: [ConvexPiece; 0] = [];
    assert_eq!(convex_pieces(&rings, &points, &mut scratch, &mut none), Err(PiecesError::BufferTooSmall { needed: 1 }));
}
