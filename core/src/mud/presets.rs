//! The paper's figures (Hirota et al. §3.3 and §4, Fig. 6, 7, 9, 10) as named presets.
//!
//! The paper prints no parameters for its figures beyond its defaults (E = 1.0e6,
//! G = 2.0e5, κ̄ = 1.02, σ = 0.001, γ = 0.9999, τ = 0.001, δx = 0.0001, α = 20) and what the
//! captions and text say each figure varies; the values below are ours where it is silent,
//! chosen so that each preset shows what its figure shows (`docs/src/models/papers.md`, Model A). Every
//! preset runs the quasi-static solver on a periodic (tileable) lattice whose domain is about
//! square: a hexagonal lattice of `c` columns has ⌈c/(√3/2)⌉ rows, rounded to an even number.
//!
//! | preset | figure | what it shows |
//! |---|---|---|
//! | `fig6a` | Fig. 6 a | hexagonal elements, the paper's defaults: isotropic closed cells |
//! | `fig6b` | Fig. 6 b | square elements, same material: axis-aligned, short, fine cracks |
//! | `fig6c` | Fig. 6 c | E/G = 10 (G halved): a larger stiffness ratio, coarser cells |
//! | `fig6d` | Fig. 6 d | E/G = 20 (G a quarter): coarser still |
//! | `fig7a` | Fig. 7 | break stretch weaker across x (ratio 2): cracks run along x |
//! | `fig7b` | Fig. 7 | the same at 60°, with stiffness anisotropy too |
//! | `fig9a` | Fig. 9 | one 64 cm plate meshed at W = 2 cm (32 columns); like fig9b–c, κ̄ − 1 scaled by (1 cm/W)^0.25 (`break_stretch_size_exponent`) |
//! | `fig9b` | Fig. 9 | the same plate at W = 1 cm (64 columns) |
//! | `fig9c` | Fig. 9 | the same plate at W = 0.5 cm (128 columns) |
//! | `fig10` | Fig. 10 | the growth process: `fig6a`'s run, drawn at increasing times |

use super::params::{MudParams, Topology};

/// Every preset name, in figure order.
pub const PRESETS: [&str; 10] =
    ["fig6a", "fig6b", "fig6c", "fig6d", "fig7a", "fig7b", "fig9a", "fig9b", "fig9c", "fig10"];

/// Nodes per row of the figures' lattices: a 96 cm plate at W = 1 cm. Cells end about 20 cm²,
/// four to five spacings across (`docs/src/models/papers.md`, Model A, Defaults), so a few hundred of
/// them: enough for a pattern, few enough to read at a few hundred pixels.
const COLUMNS: u32 = 96;

/// Rows of a hexagonal lattice whose domain is about as tall as `columns` is wide (even, as
/// periodic hexagonal lattices need).
const fn square_rows(columns: u32) -> u32 {
    // rows·√3/2 ≈ columns; √3/2 ≈ 0.866 = 433/500.
    let rows = (columns * 500 + 216) / 433;
    rows + rows % 2
}

/// Anisotropic break stretch (Fig. 7): springs across `direction` (radians) keep `1/ratio`
/// of their margin κ − 1, so cracks run along `direction`. The run stops at the crack
/// density of `fig6a` (the weakened springs break earlier), so that the two compare.
fn anisotropic(direction: f32, ratio: f32) -> MudParams {
    MudParams {
        anisotropy_direction: direction,
        anisotropy_ratio: ratio,
        target_crack_density: FIG6A_CRACK_DENSITY,
        ..hexagonal(COLUMNS)
    }
}

/// About the crack density [1/cm] `fig6a` ends at: 0.383 on its seed, as
/// [`super::MudProgress::crack_density`] counts it (the broken springs' faces per area; the
/// traced network's density is higher, 0.534).
const FIG6A_CRACK_DENSITY: f32 = 0.38;

/// A hexagonal lattice `columns` wide with the paper's defaults.
fn hexagonal(columns: u32) -> MudParams {
    MudParams { topology: Topology::Hexagonal, columns, rows: square_rows(columns), ..MudParams::default() }
}

/// The preset of that name (see [`PRESETS`]), or `None`.
pub fn preset(name: &str) -> Option<MudParams> {
    let p = match name {
        "fig6a" | "fig10" => hexagonal(COLUMNS),
        // Square elements carry no in-plane shear: the same shrink breaks fewer springs, so the
        // run goes on to 3 % for a comparable crack density.
        "fig6b" => MudParams {
            topology: Topology::Square,
            columns: COLUMNS,
            rows: COLUMNS,
            target_shrink: 0.03,
            ..MudParams::default()
        },
        "fig6c" => MudParams { shear_modulus: 1.0e5, ..hexagonal(COLUMNS) },
        "fig6d" => MudParams { shear_modulus: 5.0e4, ..hexagonal(COLUMNS) },
        "fig7a" => anisotropic(0.0, 2.0),
        "fig7b" => MudParams { stiffness_anisotropy_ratio: 2.0, ..anisotropic(core::f32::consts::FRAC_PI_3, 2.0) },
        // One 64 cm plate, three meshes (§4.2, mesh-scale independence).
        // Mesh-scale independence needs the break margin scaled to W (MudParams docs).
        "fig9a" => MudParams { element_size: 2.0, break_stretch_size_exponent: 0.25, ..hexagonal(32) },
        "fig9b" => MudParams { element_size: 1.0, break_stretch_size_exponent: 0.25, ..hexagonal(64) },
        "fig9c" => MudParams { element_size: 0.5, break_stretch_size_exponent: 0.25, ..hexagonal(128) },
        _ => return None,
    };
    Some(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_exists_and_is_valid() {
        for name in PRESETS {
            let p = preset(name).unwrap_or_else(|| panic!("{name}"));
            assert_eq!(p.validate(), Ok(()), "{name}");
            assert!(p.memory().is_ok(), "{name}");
            // The domain is about square, so that a square raster does not distort it.
            let [w, h] = p.lattice().extent();
            assert!((h / w - 1.0).abs() < 0.03, "{name}: {w} x {h}");
        }
        assert_eq!(preset("fig8"), None);
    }

    #[test]
    fn the_mesh_scale_presets_cover_one_plate() {
        let size = |name| {
            let p = preset(name).unwrap();
            p.columns as f32 * p.element_size
        };
        assert_eq!((size("fig9a"), size("fig9b"), size("fig9c")), (64.0, 64.0, 64.0));
    }
}
