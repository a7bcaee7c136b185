//! Draws a glass plate's fragments as the convex pieces a physics engine takes
//! (`hibi_core::polygon::convex_pieces`), as an SVG: each piece filled in a shade of its
//! fragment's colour, pieces outlined thinly, fragments' rings thickly.
//!
//! `cargo run --release -p hibi-cli --example pieces_svg -- docs/src/images/glass-pieces.svg`

use std::fmt::Write as _;

use hibi_core::glass::{Glass, GlassParams};
use hibi_core::polygon::{ConvexPiece, NOT_A_HOLE, Ring, convex_pieces, piece_counts, pieces_scratch};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args().nth(1).ok_or("usage: pieces_svg OUT.svg")?;
    let params = GlassParams { width: 320.0, height: 240.0, impact: [150.0, 110.0], ..GlassParams::default() };
    let memory = params.memory()?;
    let mut block = memory.allocate();
    let mut glass = Glass::new(&params, block.buffers())?;
    while !glass.step(u64::MAX).finished {}
    let mut scratch = vec![0u32; memory.scratch];
    let (r, p) = glass.fragment_counts(&mut scratch)?;
    let (mut rings, mut points) = (vec![Ring::default(); r], vec![[0.0f32; 2]; p]);
    glass.fragments(&mut scratch, &mut rings, &mut points)?;

    let mut words = vec![0u32; pieces_scratch(&rings, &points)?];
    let counts = piece_counts(&rings, &points, &mut words)?;
    let mut pieces = vec![ConvexPiece::default(); counts.pieces];
    convex_pieces(&rings, &points, &mut words, &mut pieces)?;

    let (w, h) = (params.width, params.height);
    let mut svg = String::new();
    writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="0 0 {w} {h}">"#,
        2.0 * w,
        2.0 * h
    )?;
    writeln!(svg, r##"<rect width="{w}" height="{h}" fill="#222"/>"##)?;
    let path_of = |ids: &mut dyn Iterator<Item = u32>| {
        let mut d = String::new();
        for (k, i) in ids.enumerate() {
            let [x, y] = points[i as usize];
            let _ = write!(d, "{}{x:.1},{y:.1} ", if k == 0 { "M" } else { "L" });
        }
        d + "Z"
    };
    for (n, piece) in pieces.iter().enumerate() {
        // A hue per fragment, a lightness per piece (a deterministic scramble of the indices).
        let hue = (piece.ring.wrapping_mul(2_654_435_761) >> 16) % 360;
        let light = 45 + (n as u32).wrapping_mul(40_503) % 25;
        let d = path_of(&mut piece.points[..piece.point_count as usize].iter().copied());
        writeln!(svg, r##"<path d="{d}" fill="hsl({hue},55%,{light}%)" stroke="#111" stroke-width="0.25"/>"##)?;
    }
    for ring in &rings {
        let d = path_of(&mut (ring.first_point..ring.first_point + ring.point_count));
        let colour = if ring.hole_of == NOT_A_HOLE { "#fff" } else { "#f44" };
        writeln!(svg, r#"<path d="{d}" fill="none" stroke="{colour}" stroke-width="0.8"/>"#)?;
    }
    svg.push_str("</svg>\n");
    std::fs::write(&path, svg)?;
    let holes = rings.iter().filter(|r| r.hole_of != NOT_A_HOLE).count();
    println!(
        "{path}: {} fragments ({holes} holes), {} triangles, {} convex pieces",
        rings.len() - holes,
        counts.triangles,
        counts.pieces
    );
    Ok(())
}
