//! Model C against the paper (Ishii et al.) and hibi's own acceptance criteria.

use hibi_core::Scalar;
use hibi_core::raster::{Layer, RasterError};
use hibi_core::skin::{
    PRESETS, ShadeError, ShadeParams, Skin, SkinBuffers, SkinCell, SkinError, SkinLayers, SkinParams, SkinRender,
    preset, shade,
};
use hibi_tests::fnv1a64;

/// Builds `params` (maps in `f32`) and hands the skin to `inspect`.
fn with_skin<R>(params: &SkinParams, inspect: impl FnOnce(&mut Skin) -> R) -> R {
    with_skin_in::<f32, R>(params, inspect)
}

/// Builds `params` with maps in backend `S` and hands the skin to `inspect`.
fn with_skin_in<S: Scalar, R>(params: &SkinParams, inspect: impl FnOnce(&mut Skin<S>) -> R) -> R {
    let mut memory = params.memory().expect("valid parameters").allocate();
    let mut skin = Skin::<S>::new(params, memory.buffers()).expect("memory suffices");
    assert!(!skin.run().capacity_reached, "the capacities suffice");
    inspect(&mut skin)
}

fn sized(name: &str, size: u32) -> SkinParams {
    SkinParams { width: size, height: size, ..preset(name).unwrap() }
}

/// How many cells of each level own each pixel, and (the last one of) which.
fn coverage(skin: &mut Skin) -> (Vec<Vec<u8>>, Vec<Vec<u32>>) {
    let p = *skin.params();
    let pixels = (p.width * p.height) as usize;
    let mut counts = vec![vec![0u8; pixels]; p.levels as usize];
    let mut owner = vec![vec![u32::MAX; pixels]; p.levels as usize];
    for (k, c) in skin.cells().to_vec().iter().enumerate() {
        skin.for_each_pixel(c, |x, y| {
            let i = (y * p.width + x) as usize;
            counts[c.level as usize][i] += 1;
            owner[c.level as usize][i] = k as u32;
        });
    }
    (counts, owner)
}

#[test]
fn at_every_level_each_pixel_lies_in_exactly_one_cell() {
    let mut periodic = sized("fig19a", 160);
    periodic.periodic = true;
    let cases = [
        ("fig19a", sized("fig19a", 200)),
        ("fig19b", sized("fig19b", 160)),
        ("fig19c", sized("fig19c", 160)),
        ("fig15c", sized("fig15c", 200)),
        ("periodic fig19a", periodic),
    ];
    assert_tiles(&cases);
}

/// Fig. 19 d–f stretch level 1 up to twentyfold with perturbation: a level-2 parent's outline
/// winds back and forth across its children's bisectors, and clipping it bridges the
/// crossings in one child while its sibling has the separate pieces. Bisector edges are split
/// where the parent's outline crosses them, so both see the same pieces.
#[test]
fn strongly_stretched_parents_still_tile_exactly() {
    // Periodic, level 0 twentyfold wide: a 150 px surface has room for less than one
    // spacing across, and gets two centre points (with one, each cell's neighbours across
    // were its own images, and a few pixels at the seam fell in two cells or none).
    let periodic = SkinParams { width: 150, height: 112, periodic: true, ..preset("fig19d").unwrap() };
    assert_tiles(&[
        ("periodic fig19d", periodic),
        ("fig19d", sized("fig19d", 160)),
        ("fig19e", sized("fig19e", 200)),
        ("fig19f", sized("fig19f", 200)),
    ]);
}

fn assert_tiles(cases: &[(&str, SkinParams)]) {
    for (name, p) in cases {
        with_skin(p, |skin| {
            let (counts, owner) = coverage(skin);
            for (level, counts) in counts.iter().enumerate() {
                let bad: Vec<usize> = (0..counts.len()).filter(|&i| counts[i] != 1).collect();
                assert!(
                    bad.is_empty(),
                    "{name} level {level}: {} pixels not in exactly one cell, first at {:?}",
                    bad.len(),
                    bad.first().map(|&i| (i as u32 % p.width, i as u32 / p.width))
                );
            }
            // And every cell of a finer level lies inside its parent, pixel for pixel (the
            // render reads each pixel's coarser cells as its finest cell's ancestors).
            for c in skin.cells().iter().filter(|c| c.level > 0) {
                let parent = skin.cells()[c.parent as usize];
                assert_eq!(parent.level + 1, c.level, "{name}");
            }
            for level in 1..owner.len() {
                let (coarse, fine) = (&owner[level - 1], &owner[level]);
                let strays = (0..fine.len()).filter(|&i| skin.cells()[fine[i] as usize].parent != coarse[i]).count();
                assert_eq!(strays, 0, "{name} level {level}: pixels outside their cell's parent");
            }
        });
    }
}

/// Directed outline edges of the cells of `level`, as vertex pairs.
fn edges(skin: &Skin, level: u32) -> Vec<([i64; 2], [i64; 2], usize)> {
    let mut out = Vec::new();
    for (k, c) in skin.cells().iter().enumerate().filter(|(_, c)| c.level == level) {
        let o = skin.outline(c);
        for i in 0..o.len() {
            out.push((o[i], o[(i + 1) % o.len()], k));
        }
    }
    out
}

/// Whether `v` lies exactly on the segment a–b.
fn on_segment(v: [i64; 2], a: [i64; 2], b: [i64; 2]) -> bool {
    let cross = i128::from(b[0] - a[0]) * i128::from(v[1] - a[1]) - i128::from(b[1] - a[1]) * i128::from(v[0] - a[0]);
    cross == 0 && (a[0].min(b[0])..=a[0].max(b[0])).contains(&v[0]) && (a[1].min(b[1])..=a[1].max(b[1])).contains(&v[1])
}

#[test]
fn shared_perturbed_edges_agree_from_both_sides() {
    let p = sized("fig19a", 200);
    with_skin(&p, |skin| {
        let side = 200i64 << skin.fixed_point_bits();
        for level in 0..p.levels {
            let all = edges(skin, level);
            let mut index = std::collections::HashMap::new();
            for (i, e) in all.iter().enumerate() {
                index.insert((e.0, e.1), i);
            }
            let (mut shared, mut on_parent) = (0, 0);
            for &(a, b, cell) in &all {
                if let Some(&j) = index.get(&(b, a)) {
                    assert_ne!(all[j].2, cell, "an edge and its reverse in one cell");
                    shared += 1;
                    continue;
                }
                // Not shared vertex for vertex: it must run along the surface's border or its
                // parent's outline (where neighbouring parents' children meet at T-junctions,
                // exactly on the parent's edge).
                let border = |v: [i64; 2]| v[0] == 0 || v[1] == 0 || v[0] == side || v[1] == side;
                if border(a) && border(b) {
                    continue;
                }
                let c: &SkinCell = &skin.cells()[cell];
                assert!(c.level > 0, "level-0 edge {a:?}→{b:?} of cell {cell} has no twin");
                let parent = skin.outline(&skin.cells()[c.parent as usize]);
                let along = (0..parent.len()).any(|i| {
                    let (x, y) = (parent[i], parent[(i + 1) % parent.len()]);
                    on_segment(a, x, y) && on_segment(b, x, y)
                });
                assert!(
                    along,
                    "level {level}: edge {a:?}→{b:?} of cell {cell} is neither shared nor on its parent's outline"
                );
                on_parent += 1;
            }
            println!("level {level}: {shared} shared edges, {on_parent} along a parent's outline");
            assert!(shared > all.len() / 2, "level {level}");
        }
    });
}

/// Mean height/width ratio of the bounding boxes of level-0 cells away from the border.
fn mean_aspect(p: &SkinParams) -> f64 {
    with_skin(p, |skin| {
        let side = i64::from(p.width) << skin.fixed_point_bits();
        let mut ratios = Vec::new();
        for c in skin.cells().iter().filter(|c| c.level == 0) {
            let o = skin.outline(c);
            let (x0, x1) = (o.iter().map(|v| v[0]).min().unwrap(), o.iter().map(|v| v[0]).max().unwrap());
            let (y0, y1) = (o.iter().map(|v| v[1]).min().unwrap(), o.iter().map(|v| v[1]).max().unwrap());
            if x0 > 0 && y0 > 0 && x1 < side && y1 < side {
                ratios.push((y1 - y0) as f64 / (x1 - x0) as f64);
            }
        }
        assert!(ratios.len() > 10, "{} interior cells", ratios.len());
        ratios.iter().sum::<f64>() / ratios.len() as f64
    })
}

#[test]
fn stretch_1_3_makes_cells_about_three_times_taller_than_wide() {
    let round = mean_aspect(&sized("fig17a", 400));
    let tall = mean_aspect(&sized("fig17b", 400));
    let wide = mean_aspect(&sized("fig17c", 400));
    println!("height/width: stretch (1,1) {round:.2}, (1,3) {tall:.2}, (3,1) {wide:.2}");
    assert!((tall / round - 3.0).abs() < 0.3, "(1,3) vs (1,1): {:.2}", tall / round);
    assert!((round / wide - 3.0).abs() < 0.3, "(1,1) vs (3,1): {:.2}", round / wide);
}

#[test]
fn more_levels_give_more_cells() {
    let counts: Vec<usize> =
        ["fig18a", "fig18b", "fig18c"].iter().map(|n| with_skin(&sized(n, 200), |s| s.cells().len())).collect();
    println!("cells with 1, 2, 3 levels: {counts:?}");
    assert!(counts[1] > 4 * counts[0] && counts[2] > 4 * counts[1], "{counts:?}");
}

/// Height and normal maps of a skin.
fn maps<S: Scalar>(skin: &Skin<S>) -> (Vec<f32>, Vec<[f32; 3]>) {
    let n = (skin.params().width * skin.params().height) as usize;
    let (mut h, mut nm) = (vec![0.0f32; n], vec![[0.0f32; 3]; n]);
    skin.render(
        &SkinRender::default(),
        SkinLayers { height: Some(&mut h), normal: Some(&mut nm), ..SkinLayers::default() },
    )
    .unwrap();
    (h, nm)
}

/// A render only reads the skin: four threads render one skin at once and get the maps one
/// render alone gets.
#[test]
fn renders_share_the_skin_across_threads() {
    with_skin(&sized("fig19a", 96), |skin| {
        let alone = maps(skin);
        let skin = &*skin;
        let together = hibi_tests::on_four_threads(|| maps(skin));
        assert!(together.iter().all(|m| *m == alone));
    });
}

/// The render draws the finest cells and reads each pixel's coarser cells as their
/// ancestors: every map is the same whether it is asked for alone or with the others, and the
/// cell map of each level names the cell that owns the pixel.
#[test]
fn each_map_is_the_same_alone_or_with_the_others() {
    let mut periodic = sized("fig19b", 120);
    periodic.periodic = true;
    let cases = [("fig19a", sized("fig19a", 150)), ("fig19f", sized("fig19f", 150)), ("periodic fig19b", periodic)];
    for (name, p) in cases {
        with_skin(&p, |skin| {
            let (together_h, together_n) = maps(skin);
            let n = together_h.len();
            let (mut h, mut nm) = (vec![-1.0f32; n], vec![[-1.0f32; 3]; n]);
            skin.render(&SkinRender::default(), SkinLayers { height: Some(&mut h), ..SkinLayers::default() }).unwrap();
            skin.render(&SkinRender::default(), SkinLayers { normal: Some(&mut nm), ..SkinLayers::default() }).unwrap();
            let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert!(bits(&h) == bits(&together_h), "{name}: heights alone");
            assert!(bits(nm.as_flattened()) == bits(together_n.as_flattened()), "{name}: normals alone");
            let (_, owner) = coverage(skin);
            for level in 0..p.levels {
                let (mut alone, mut with) = (vec![0u32; n], vec![0u32; n]);
                skin.render(
                    &SkinRender { cell_level: level, ..SkinRender::default() },
                    SkinLayers { cell: Some(&mut alone), ..SkinLayers::default() },
                )
                .unwrap();
                let layers = SkinLayers {
                    height: Some(&mut h),
                    normal: Some(&mut nm),
                    cell: Some(&mut with),
                    ..SkinLayers::default()
                };
                skin.render(&SkinRender { cell_level: level, ..SkinRender::default() }, layers).unwrap();
                assert!(alone == owner[level as usize], "{name}: cell map of level {level}");
                assert!(with == alone, "{name}: cell map of level {level} with the other maps");
                assert!(bits(&h) == bits(&together_h), "{name}: heights with cell map {level}");
            }
        });
    }
}

#[test]
fn a_periodic_surface_has_no_seam() {
    let mut p = sized("fig19a", 160);
    p.periodic = true;
    with_skin(&p, |skin| {
        let (h, _) = maps(skin);
        let w = p.width as usize;
        // Height steps across the wrap (last column to first, last row to first) against steps
        // between neighbouring columns and rows inside.
        let step = |a: usize, b: usize| f64::from((h[a] - h[b]).abs());
        let (mut inside, mut across) = (0.0, 0.0);
        for k in 0..w {
            for x in 0..w - 1 {
                inside += step(k * w + x, k * w + x + 1) + step(x * w + k, (x + 1) * w + k);
            }
            across += step(k * w + w - 1, k * w) + step((w - 1) * w + k, k);
        }
        let (inside, across) = (inside / (2.0 * (w * (w - 1)) as f64), across / (2.0 * w as f64));
        println!("mean height step: inside {inside:.3}, across the wrap {across:.3}");
        assert!(across < 1.5 * inside, "seam: {across} vs {inside}");
    });
    // Not periodic: the edges are cut.
    let q = sized("fig19a", 160);
    with_skin(&q, |skin| assert!(coverage(skin).0.iter().all(|c| c.iter().all(|&k| k == 1))));
}

#[test]
fn heights_and_normals_follow_the_profile() {
    let p = sized("fig13b", 200);
    with_skin(&p, |skin| {
        let (h, n) = maps(skin);
        // Fig. 13 b: a plateau at 3 falling to 0 at the furrows.
        let max = h.iter().cloned().fold(f32::MIN, f32::max);
        let min = h.iter().cloned().fold(f32::MAX, f32::min);
        assert!((max - 3.0).abs() < 1e-3 && min < 0.3, "{min} .. {max}");
        assert!(n.iter().all(|v| ((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - 1.0).abs() < 1e-4 && v[2] > 0.0));
        // On the plateau the normal points straight up.
        for (i, z) in h.iter().enumerate() {
            if *z > 2.999 {
                assert!(n[i][2] > 0.999, "pixel {i}: {:?}", n[i]);
            }
        }
        // The normals lean away from each cell's centre (the ridge falls towards its edge).
        let unit = (1i64 << skin.fixed_point_bits()) as f64;
        let mut outward = 0usize;
        let mut total = 0usize;
        for c in &skin.cells().to_vec() {
            let centre = [c.centre[0] as f64 / unit, c.centre[1] as f64 / unit];
            skin.for_each_pixel(c, |x, y| {
                let i = (y * p.width + x) as usize;
                if n[i][2] < 0.95 {
                    // y flips: the normal map is y-up, the raster y-down.
                    let d = [x as f64 + 0.5 - centre[0], -(y as f64 + 0.5 - centre[1])];
                    total += 1;
                    outward += usize::from(d[0] * f64::from(n[i][0]) + d[1] * f64::from(n[i][1]) > 0.0);
                }
            });
        }
        assert!(outward as f64 > 0.99 * total as f64, "{outward} of {total}");
    });
}

#[test]
fn f32_and_q16_agree_and_each_has_its_golden() {
    let p = sized("fig19a", 96);
    with_skin(&p, |skin| {
        let hash = |(h, n): &(Vec<f32>, Vec<[f32; 3]>)| {
            let mut bytes = Vec::new();
            for v in h {
                bytes.extend(v.to_bits().to_le_bytes());
            }
            for v in n.iter().flatten() {
                bytes.extend(v.to_bits().to_le_bytes());
            }
            fnv1a64(&bytes)
        };
        let f = maps(skin);
        let q = with_skin_in::<hibi_core::scalar::Q16, _>(&p, |s| maps(s));
        let worst = f.0.iter().zip(&q.0).map(|(a, b)| (a - b).abs()).fold(0.0f32, f32::max);
        println!("Q16 vs f32 height: worst {worst}");
        assert!(worst < 0.02, "{worst}");
        let mut cells = Vec::new();
        for c in skin.cells() {
            cells.extend(c.site.to_le_bytes());
            for v in skin.outline(c) {
                cells.extend(v[0].to_le_bytes());
                cells.extend(v[1].to_le_bytes());
            }
        }
        let got = (fnv1a64(&cells), hash(&f), hash(&q));
        println!("goldens: {got:?}");
        assert_eq!(
            got,
            (4609634658128003714, 2866373228789025190, 10947300996238655645),
            "the skin scene changed (outlines, f32 maps, Q16 maps)"
        );
    });
}

#[test]
fn bad_input_is_refused_and_nothing_is_written() {
    let p = sized("fig19a", 64);
    let m = p.memory().unwrap();
    let mut cells = vec![Default::default(); m.cells];
    let mut vertices = vec![[7i64; 2]; m.vertices - 1];
    let (mut sites, mut clip, mut words) =
        (vec![Default::default(); m.sites], vec![Default::default(); m.clip], vec![0u32; m.words]);
    let mut levels = vec![Default::default(); m.levels];
    let (mut divisions, mut shared_edges) =
        (vec![Default::default(); m.divisions], vec![Default::default(); m.shared_edges]);
    let mut boxes = vec![[0; 4]; m.boxes];
    let mut wedges = vec![Default::default(); m.wedges];
    let buffers = SkinBuffers {
        cells: &mut cells,
        vertices: &mut vertices,
        sites: &mut sites,
        clip: &mut clip,
        words: &mut words,
        levels: &mut levels,
        divisions: &mut divisions,
        shared_edges: &mut shared_edges,
        boxes: &mut boxes,
        wedges: &mut wedges,
    };
    assert_eq!(Skin::<f32>::new(&p, buffers).err(), Some(SkinError::BufferTooSmall { needed: m.vertices }));
    assert!(vertices.iter().all(|v| *v == [7, 7]));
    let bad = SkinParams { levels: 9, ..p };
    assert!(bad.memory().is_err());
    with_skin(&p, |skin| {
        let mut short = vec![5.0f32; 64 * 64 - 1];
        let mut normal = vec![[5.0f32; 3]; 64 * 64];
        let layers = SkinLayers { height: Some(&mut short), normal: Some(&mut normal), ..SkinLayers::default() };
        let short_height = RasterError::BufferTooSmall { layer: Layer::Height, needed: 64 * 64 };
        assert_eq!(skin.render(&SkinRender::default(), layers), Err(SkinError::Raster(short_height)));
        assert!(short.iter().all(|&v| v == 5.0) && normal.iter().all(|v| *v == [5.0; 3]));
        let mut ids = vec![9u32; 64 * 64];
        let layers = SkinLayers { cell: Some(&mut ids), ..SkinLayers::default() };
        assert_eq!(skin.render(&SkinRender { cell_level: 3, ..SkinRender::default() }, layers), Err(SkinError::Level));
        assert!(ids.iter().all(|&v| v == 9));
        let (h, n) = maps(skin);
        let mut rgb = vec![[1u8; 3]; 64 * 64];
        let dark = ShadeParams { light: [0.0; 3], ..ShadeParams::default() };
        assert_eq!(shade(&h, &n, &dark, &mut rgb), Err(SkinError::Shade(ShadeError::Light)));
        let refused = [
            (ShadeParams { ridge: [0.5, 1.01, 0.5], ..ShadeParams::default() }, ShadeError::Ridge),
            (ShadeParams { furrow: [0.5, 0.5, -0.01], ..ShadeParams::default() }, ShadeError::Furrow),
            (ShadeParams { ambient: f32::NAN, ..ShadeParams::default() }, ShadeError::Ambient),
            (ShadeParams { specular: -1.0, ..ShadeParams::default() }, ShadeError::Specular),
        ];
        for (bad, error) in refused {
            assert_eq!(shade(&h, &n, &bad, &mut rgb), Err(SkinError::Shade(error)));
        }
        assert!(rgb.iter().all(|v| *v == [1; 3]));
        shade(&h, &n, &ShadeParams::default(), &mut rgb).unwrap();
        assert!(rgb.iter().any(|v| *v != [1; 3]));
    });
}

#[test]
fn every_preset_builds_and_renders() {
    for name in PRESETS {
        let p = sized(name, 96);
        with_skin(&p, |skin| {
            let (h, _) = maps(skin);
            assert!(h.iter().all(|v| v.is_finite()) && h.iter().any(|&v| v > 0.5), "{name}");
        });
    }
}

/// A full-size fig19a skin builds and renders on a thread of 32 KiB: its build scratch is in
/// caller memory, a render's few KiB on the stack (tests/stack.rs measures each function). An overflow aborts the test run.
#[test]
fn a_fig19a_skin_builds_and_renders_in_a_32_kib_stack() {
    let cells = std::thread::Builder::new()
        .stack_size(32 * 1024)
        .spawn(|| {
            let p = preset("fig19a").unwrap();
            with_skin(&p, |skin| {
                let n = (p.width * p.height) as usize;
                let (mut h, mut nm, mut c) = (vec![0.0f32; n], vec![[0.0f32; 3]; n], vec![0u32; n]);
                let layers = SkinLayers {
                    height: Some(&mut h),
                    normal: Some(&mut nm),
                    cell: Some(&mut c),
                    ..SkinLayers::default()
                };
                skin.render(&SkinRender { cell_level: 2, ..SkinRender::default() }, layers).unwrap();
                assert!(c.iter().all(|&i| i != hibi_core::skin::NO_CELL));
                skin.cells().len()
            })
        })
        .unwrap()
        .join()
        .unwrap();
    assert!(cells > 10_000, "{cells}");
}

/// The environment variable that makes [`a_unit_costs_about_the_same_at_every_spacing_ratio`],
/// run under Callgrind by itself, build one case (its index) instead of measuring them all.
const UNIT_CASE: &str = "HIBI_SKIN_UNIT_CASE";

/// Two-level skins (level 0 at the default 40 px) whose level-1 spacing makes a parent hold
/// from about one child (40) to about 1 800 (1), and the default two-level skin (40 / 3).
fn unit_cases() -> Vec<(&'static str, SkinParams)> {
    let two = SkinParams { width: 120, height: 120, levels: 2, ..SkinParams::default() };
    let spaced = |s: f32| {
        let mut p = two;
        p.level[1].spacing = s;
        p
    };
    vec![
        ("default (level 1 at 40/3)", two),
        ("level 1 at 1", spaced(1.0)),
        ("level 1 at 5", spaced(5.0)),
        ("level 1 at 8", spaced(8.0)),
        ("level 1 at 40", spaced(40.0)),
    ]
}

/// Steps `skin` with budgets of 10 000 until it is finished or has done `limit` units; the
/// only function Callgrind counts in [`a_unit_costs_about_the_same_at_every_spacing_ratio`]
/// (found by its unmangled name).
#[unsafe(no_mangle)]
#[inline(never)]
fn hibi_test_skin_unit_steps(skin: &mut Skin, limit: u64) -> hibi_core::skin::SkinProgress {
    loop {
        let progress = skin.step(10_000);
        if progress.finished || progress.work >= limit {
            return progress;
        }
    }
}

/// What one unit of `Skin::step` costs, in instructions (Callgrind, so the same on any
/// machine): a cell's neighbours are found among its siblings near it, whatever the number
/// of siblings, so a unit costs about the same whether a parent holds one child or 1 800.
/// Each case is built under Callgrind by this test binary itself (the case named by
/// [`UNIT_CASE`]), counting `hibi_test_skin_unit_steps` alone, up to 60 000 units; its
/// instructions per unit must be within 10 times those of every other case. (In the debug
/// profile the random-number crates are not optimised, so the lattice's draws weigh more per
/// unit where a parent holds few children: about 4 500 instructions a unit at 1 px, 16 000
/// at 40. Sorting all siblings for each child would cost 1 px about 168 000.)
#[test]
fn a_unit_costs_about_the_same_at_every_spacing_ratio() {
    const LIMIT: u64 = 60_000;
    let cases = unit_cases();
    if let Ok(case) = std::env::var(UNIT_CASE) {
        // Under Callgrind: build the case and report its work.
        let (_, p) = cases[case.parse::<usize>().expect("a case index")];
        let mut memory = p.memory().expect("valid parameters").allocate();
        let mut skin: Skin = Skin::new(&p, memory.buffers()).expect("memory suffices");
        let progress = hibi_test_skin_unit_steps(&mut skin, LIMIT);
        assert!(!progress.capacity_reached && progress.work > 100, "{progress:?}");
        println!("\nskin unit work {}", progress.work);
        return;
    }
    let mut per_unit = Vec::new();
    for (k, (name, _)) in cases.iter().enumerate() {
        let (stdout, instructions) = hibi_tests::callgrind_this_test(
            "a_unit_costs_about_the_same_at_every_spacing_ratio",
            "hibi_test_skin_unit_steps",
            (UNIT_CASE, &k.to_string()),
        );
        let work: u64 = stdout
            .lines()
            .find_map(|l| l.split_once("skin unit work ").map(|(_, w)| w))
            .and_then(|w| w.trim().parse().ok())
            .unwrap_or_else(|| panic!("{name}: no work reported in\n{stdout}"));
        // (Collection was on: the build's instructions are far more than its units.)
        assert!(instructions > 100 * work, "{name}: {instructions} instructions for {work} units");
        let cost = instructions as f64 / work as f64;
        println!("{name}: {work} units, {instructions} instructions, {cost:.0} per unit");
        per_unit.push((*name, cost));
    }
    let cheapest = per_unit.iter().map(|c| c.1).fold(f64::INFINITY, f64::min);
    let dearest = per_unit.iter().map(|c| c.1).fold(0.0, f64::max);
    assert!(dearest <= 10.0 * cheapest, "instructions per unit from {cheapest:.0} to {dearest:.0}: {per_unit:?}");
}

/// The signed areas of one level's cell outlines, summed in f64, in pixels².
fn level_areas(skin: &Skin) -> Vec<f64> {
    let unit = (1u64 << skin.fixed_point_bits()) as f64;
    let mut sums = vec![0.0f64; skin.params().levels as usize];
    for cell in skin.cells() {
        let o = skin.outline(cell);
        let twice: f64 = (0..o.len())
            .map(|i| {
                let (a, b) = (o[i], o[(i + 1) % o.len()]);
                a[0] as f64 * b[1] as f64 - b[0] as f64 * a[1] as f64
            })
            .sum();
        sums[cell.level as usize] += 0.5 * twice / (unit * unit);
    }
    sums
}

/// The cells of every level tile the surface: their outlines' areas add up to width × height
/// within 1e-4, summed in f64, for the defaults and every preset (at 200 × 200), open and
/// periodic, and at the extremes the validation accepts (a perturbation of 10³⁰, a stretch of
/// 10³⁰ and of 10⁻³, two levels 40 px and 1 px apart).
#[test]
fn the_cells_of_every_level_cover_the_surface() {
    let mut cases: Vec<(String, SkinParams)> = vec![("defaults".into(), SkinParams::default())];
    cases.extend(PRESETS.iter().map(|&name| (name.to_string(), preset(name).expect("a preset"))));
    let base = SkinParams { width: 160, height: 160, ..SkinParams::default() };
    type Extreme = (&'static str, fn(&mut SkinParams));
    let extremes: [Extreme; 4] = [
        ("perturbation 1e30", |p| p.level[0].perturbation = 1e30),
        ("stretch 1e30", |p| p.level[0].stretch = [1e30, 1e30]),
        ("stretch 1e-3", |p| p.level[0].stretch = [1e-3, 1.0]),
        ("1 px under 40", |p| (p.levels, p.level[0].spacing, p.level[1].spacing) = (2, 40.0, 1.0)),
    ];
    for (name, change) in extremes {
        let mut p = base;
        change(&mut p);
        cases.push((name.to_string(), p));
    }
    for (name, mut p) in cases {
        (p.width, p.height) = (p.width.min(200), p.height.min(200));
        for periodic in [false, true] {
            p.periodic = periodic;
            let mut memory = p.memory().expect("valid parameters").allocate();
            let mut skin: Skin = Skin::new(&p, memory.buffers()).expect("memory suffices");
            let progress = skin.run();
            assert!(progress.finished && !progress.capacity_reached, "{name}: {progress:?}");
            let surface = f64::from(p.width) * f64::from(p.height);
            for (level, area) in level_areas(&skin).into_iter().enumerate() {
                assert!(
                    (area / surface - 1.0).abs() <= 1e-4,
                    "{name}, periodic {periodic}, level {level}: {area} of {surface}"
                );
            }
        }
    }
}
