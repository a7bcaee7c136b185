//! Every layer of every model in one render call, and tiles: a render of any sub-rectangle of
//! the image gives, bit for bit, the pixels the whole image's render gives there, for every
//! layer, on open and periodic domains, at the edges and corners.

use hibi_core::glass::{Glass, GlassParams, GlassRender};
use hibi_core::mud::{Boundary, Mud, MudParams, MudRender};
use hibi_core::raster::{Layer, Layers, RasterError, Tile};
use hibi_core::skin::{Skin, SkinError, SkinParams, SkinRender, preset};
use hibi_tests::EveryLayer;

/// Tiles of a `width × height` image: corners, edges, single pixels, strips, the middle.
fn tiles(width: u32, height: u32) -> Vec<Tile> {
    let t = |x, y, w, h| Tile { x, y, width: w, height: h };
    vec![
        t(0, 0, 1, 1),
        t(width - 1, height - 1, 1, 1),
        t(0, 0, 17, 9),
        t(width - 13, height - 7, 13, 7),
        t(width - 5, 0, 5, height),
        t(0, height / 2, width, 3),
        t(width / 3, height / 4, width / 3, height / 2),
        t(1, 1, width - 2, height - 2),
        t(0, 0, width, height),
    ]
}

/// Renders the whole image and each tile with every layer the model has, and checks that
/// each tile's pixels equal the whole image's, bit for bit; returns the whole image.
fn tiles_match(
    width: u32,
    height: u32,
    crack: bool,
    render: impl Fn(&Tile, Layers) -> Result<(), String>,
) -> EveryLayer {
    let mut whole = EveryLayer::new(width, height);
    render(&Tile::whole(width, height), whole.layers(crack)).expect("the whole image renders");
    for tile in tiles(width, height) {
        let mut part = EveryLayer::new(tile.width, tile.height);
        render(&tile, part.layers(crack)).expect("a tile renders");
        for y in 0..tile.height {
            for x in 0..tile.width {
                assert_eq!(
                    part.pixel(tile.width, x, y),
                    whole.pixel(width, tile.x + x, tile.y + y),
                    "{tile:?}: pixel ({x}, {y}) differs from the whole image's"
                );
            }
        }
    }
    whole
}

/// Renders each layer alone (with the scratch) over the whole image and checks that it is,
/// byte for byte, what the render of every layer at once wrote: no layer depends on the others
/// asked for with it (the preview reads the mask when both are drawn, and draws its coverage
/// itself otherwise).
fn each_layer_alone(whole: &EveryLayer, width: u32, height: u32, crack: bool, render: impl Fn(Layers)) {
    for k in 0..7 {
        let mut alone = EveryLayer::new(width, height);
        let e = &mut alone;
        let mut layers = Layers { scratch: Some(&mut e.scratch), ..Layers::default() };
        match k {
            0 => layers.mask = Some(&mut e.mask),
            1 => layers.height = Some(&mut e.height),
            2 => layers.height16 = Some(&mut e.height16),
            3 => layers.normal = Some(&mut e.normal),
            4 => layers.normal_rgb8 = Some(&mut e.normal_rgb8),
            5 if crack => layers.time = Some(&mut e.time),
            5 => layers.cell = Some(&mut e.cell),
            _ => layers.preview = Some(&mut e.preview),
        }
        render(layers);
        let same = match k {
            0 => alone.mask == whole.mask,
            1 => alone.height.iter().map(|v| v.to_bits()).eq(whole.height.iter().map(|v| v.to_bits())),
            2 => alone.height16 == whole.height16,
            3 => alone.normal.iter().flatten().map(|v| v.to_bits()).eq(whole
                .normal
                .iter()
                .flatten()
                .map(|v| v.to_bits())),
            4 => alone.normal_rgb8 == whole.normal_rgb8,
            5 if crack => alone.time.iter().map(|v| v.to_bits()).eq(whole.time.iter().map(|v| v.to_bits())),
            5 => alone.cell == whole.cell,
            _ => alone.preview == whole.preview,
        };
        assert!(same, "layer {k} alone differs from the same layer drawn with every other");
    }
}

fn finished_mud(params: &MudParams, run: impl FnOnce(&Mud)) {
    let mut store = params.memory().expect("valid").allocate::<f32>();
    let mut mud = Mud::new(params, store.buffers()).expect("memory suffices");
    mud.run().expect("the run ends");
    run(&mud);
}

#[test]
fn mud_tiles_equal_the_whole_image_open_and_periodic() {
    for boundary in [Boundary::Open, Boundary::Periodic] {
        let params = MudParams { columns: 32, rows: 32, boundary, seed: 3, ..MudParams::default() };
        finished_mud(&params, |mud| {
            let render = MudRender { offset: [1.5, -2.25], ..MudRender::fit(mud.extent(), 96) };
            let whole = tiles_match(render.width, render.height, true, |tile, layers| {
                mud.render_tile(&render, tile, layers).map_err(|e| e.to_string())
            });
            assert!(whole.mask.contains(&255), "{boundary:?}: cracks are drawn");
            assert!(whole.preview.iter().all(|p| p[3] == 255));
            each_layer_alone(&whole, render.width, render.height, true, |layers| mud.render(&render, layers).unwrap());
            // The layers of one pass are those of separate calls.
            let mut mask = vec![0u8; whole.mask.len()];
            mud.render(&render, Layers { mask: Some(&mut mask), ..Layers::default() }).unwrap();
            assert_eq!(mask, whole.mask);
            let mut height = vec![0f32; whole.mask.len()];
            mud.render(&render, Layers { height: Some(&mut height), ..Layers::default() }).unwrap();
            assert_eq!(height, whole.height, "{boundary:?}: height without the scratch");
        });
    }
}

#[test]
fn glass_tiles_equal_the_whole_image() {
    let params = GlassParams { width: 120.0, height: 90.0, impact: [50.0, 40.0], seed: 5, ..GlassParams::default() };
    let mut store = params.memory().expect("valid").allocate();
    let mut glass = Glass::new(&params, store.buffers()).expect("memory");
    glass.run();
    let render = GlassRender { width: 120, height: 90, ..GlassRender::default() };
    let whole =
        tiles_match(120, 90, true, |tile, layers| glass.render_tile(&render, tile, layers).map_err(|e| e.to_string()));
    assert!(whole.mask.contains(&255));
    each_layer_alone(&whole, 120, 90, true, |layers| glass.render(&render, layers).unwrap());
    // Height is 1 − coverage, exactly.
    for (h, m) in whole.height.iter().zip(&whole.mask) {
        assert_eq!(*h, 1.0 - f32::from(*m) / 255.0);
    }
}

#[test]
fn skin_tiles_equal_the_whole_surface_open_and_periodic() {
    for periodic in [false, true] {
        let params = SkinParams { width: 90, height: 70, periodic, ..preset("fig19a").expect("a preset") };
        let mut store = params.memory().expect("valid").allocate();
        let mut skin = Skin::<f32>::new(&params, store.buffers()).expect("memory");
        skin.run();
        let render = SkinRender { cell_level: 1, ..SkinRender::default() };
        let whole = tiles_match(90, 70, false, |tile, layers| {
            skin.render_tile(&render, tile, layers).map_err(|e| e.to_string())
        });
        // Furrows: the coarsest level's outlines at 255, and cells inside them left dark.
        assert!(whole.mask.contains(&255) && whole.mask.contains(&0));
        assert!(whole.cell.iter().all(|&c| (c as usize) < skin.cells().len()));
        each_layer_alone(&whole, 90, 70, false, |layers| skin.render(&render, layers).unwrap());
    }
}

#[test]
fn a_model_refuses_a_layer_it_does_not_draw_and_bad_tiles_and_writes_nothing() {
    let params = GlassParams { width: 40.0, height: 40.0, impact: [20.0; 2], ..GlassParams::default() };
    let mut store = params.memory().expect("valid").allocate();
    let mut glass = Glass::new(&params, store.buffers()).expect("memory");
    glass.run();
    let render = GlassRender { width: 40, height: 40, ..GlassRender::default() };
    let mut every = EveryLayer::new(40, 40);
    let untouched = every.clone();
    let mut layers = every.layers(true);
    let mut cell = vec![7u32; 1600];
    layers.cell = Some(&mut cell);
    assert_eq!(glass.render(&render, layers), Err(RasterError::NoLayer(Layer::Cell)));
    assert_eq!(every, untouched);
    for tile in [Tile { x: 30, y: 0, width: 11, height: 1 }, Tile { x: 0, y: 0, width: 0, height: 4 }] {
        assert_eq!(glass.render_tile(&render, &tile, every.layers(true)), Err(RasterError::Tile), "{tile:?}");
    }
    let mut short = every.clone();
    short.scratch.pop();
    assert_eq!(
        glass.render(&render, short.layers(true)),
        Err(RasterError::BufferTooSmall { layer: Layer::Scratch, needed: 42 * 42 })
    );
    let mut no_scratch = every.layers(true);
    no_scratch.scratch = None;
    assert_eq!(
        glass.render(&render, no_scratch),
        Err(RasterError::BufferTooSmall { layer: Layer::Scratch, needed: 42 * 42 })
    );
    assert_eq!(every, untouched);

    let params = SkinParams { width: 32, height: 32, ..preset("fig19a").expect("a preset") };
    let mut store = params.memory().expect("valid").allocate();
    let mut skin = Skin::<f32>::new(&params, store.buffers()).expect("memory");
    skin.run();
    let mut every = EveryLayer::new(32, 32);
    let mut layers = every.layers(false);
    let mut time = vec![0f32; 1024];
    layers.time = Some(&mut time);
    assert_eq!(skin.render(&SkinRender::default(), layers), Err(SkinError::Raster(RasterError::NoLayer(Layer::Time))));
}

#[test]
fn until_draws_the_cracks_as_they_stood() {
    let params = MudParams { columns: 32, rows: 32, seed: 9, ..MudParams::default() };
    finished_mud(&params, |mud| {
        let render = MudRender::fit(mud.extent(), 64);
        let pixels = (render.width * render.height) as usize;
        let (mut time, mut all) = (vec![0f32; pixels], vec![0u8; pixels]);
        mud.render(&render, Layers { time: Some(&mut time), mask: Some(&mut all), ..Layers::default() }).unwrap();
        let finite: Vec<f32> = time.iter().copied().filter(|t| t.is_finite()).collect();
        let (first, last) = finite.iter().fold((f32::MAX, f32::MIN), |(a, b), &t| (a.min(t), b.max(t)));
        let mut previous = 0usize;
        for k in 0..=4 {
            let until = first + (last - first) * k as f32 / 4.0;
            let mut mask = vec![0u8; pixels];
            mud.render(&MudRender { until, ..render }, Layers { mask: Some(&mut mask), ..Layers::default() }).unwrap();
            let drawn = mask.iter().filter(|&&m| m > 0).count();
            assert!(drawn >= previous, "the cracks grow: {drawn} < {previous}");
            // Every pixel whose time map says it broke by then is drawn.
            for i in 0..pixels {
                if time[i] <= until {
                    assert!(mask[i] > 0, "pixel {i} broke at {} <= {until}", time[i]);
                }
                assert!(mask[i] <= all[i]);
            }
            previous = drawn;
        }
        assert!(previous == all.iter().filter(|&&m| m > 0).count());
    });
}

/// The case the Callgrind test below runs in this binary: `model:image` (`image` the image's
/// width, or `tile` for a 64 × 64 tile of a 4096-wide image).
const TILE_CASE: &str = "HIBI_TILE_COST_CASE";

/// Renders every layer of `tile` of a model (wrapped so that Callgrind can count it alone).
#[unsafe(no_mangle)]
#[inline(never)]
fn hibi_test_render_tile(draw: &dyn Fn(&Tile, Layers), tile: &Tile) {
    let mut every = EveryLayer::new(tile.width, tile.height);
    draw(tile, every.layers(!matches!(std::env::var(TILE_CASE).as_deref(), Ok(c) if c.starts_with("skin"))));
    std::hint::black_box(&every);
}

/// A render's cost is set by its tile, not by the image: every layer of a 64 × 64 tile of a
/// 4096-pixel-wide image takes fewer instructions (Callgrind, the same on any machine) than
/// the whole of a 256-wide one, for mud and glass; a skin's tile, a sixteenth of its 400 × 400
/// surface, takes less than a third of the whole (each render also passes over every cell).
#[test]
fn a_tile_costs_what_its_pixels_do_not_what_the_image_does() {
    if let Ok(case) = std::env::var(TILE_CASE) {
        let (model, size) = case.split_once(':').expect("model:size");
        let huge = size == "tile";
        match model {
            "mud" => finished_mud(&MudParams::default(), |mud| {
                let render = MudRender::fit(mud.extent(), if huge { 4096 } else { 256 });
                let tile = if huge {
                    Tile { x: 2000, y: 1500, width: 64, height: 64 }
                } else {
                    Tile::whole(render.width, render.height)
                };
                hibi_test_render_tile(&|t, l| mud.render_tile(&render, t, l).expect("renders"), &tile);
            }),
            "glass" => {
                let params = GlassParams::default();
                let mut store = params.memory().expect("valid").allocate();
                let mut glass = Glass::new(&params, store.buffers()).expect("memory");
                glass.run();
                let side = if huge { 4096 } else { 256 };
                let render = GlassRender { width: side, height: side, ..GlassRender::default() };
                let tile =
                    if huge { Tile { x: 2000, y: 2000, width: 64, height: 64 } } else { Tile::whole(side, side) };
                hibi_test_render_tile(&|t, l| glass.render_tile(&render, t, l).expect("renders"), &tile);
            }
            _ => {
                let params = preset("fig19a").expect("a preset");
                let mut store = params.memory().expect("valid").allocate();
                let mut skin = Skin::<f32>::new(&params, store.buffers()).expect("memory");
                skin.run();
                let tile = if huge { Tile { x: 150, y: 150, width: 100, height: 100 } } else { Tile::whole(400, 400) };
                let render = SkinRender::default();
                hibi_test_render_tile(&|t, l| skin.render_tile(&render, t, l).expect("renders"), &tile);
            }
        }
        println!("\nrendered {case}");
        return;
    }
    for (model, limit) in [("mud", 1.0), ("glass", 1.0), ("skin", 1.0 / 3.0)] {
        let count = |size: &str| {
            let case = format!("{model}:{size}");
            let (stdout, instructions) = hibi_tests::callgrind_this_test(
                "a_tile_costs_what_its_pixels_do_not_what_the_image_does",
                "hibi_test_render_tile",
                (TILE_CASE, &case),
            );
            assert!(stdout.contains(&format!("rendered {case}")), "{case}: {stdout}");
            instructions
        };
        let (whole, tile) = (count("whole"), count("tile"));
        println!("{model}: whole image {whole} instructions, tile {tile} ({:.3} of it)", tile as f64 / whole as f64);
        assert!((tile as f64) < limit * whole as f64, "{model}: a tile took {tile} instructions, the whole {whole}");
    }
}
