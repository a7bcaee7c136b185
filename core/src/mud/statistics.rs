//! Crack statistics measured on the traced network and its cells (see [`super::network`] and
//! [`super::cells`]), independent of any drawing.

use super::Mud;
use crate::scalar::Scalar;

/// Crack statistics of a run's traced network.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CrackStatistics {
    /// Crack length per area [1/cm]: the network's length (its edges' polylines, branches
    /// included) over the plate's area.
    pub crack_density: f32,
    /// Cells: the regions the separating cracks enclose (outer rings), wrapping ones included.
    pub cells: u32,
    /// Mean area of a cell \[cm²\]: the plate's area over the number of cells.
    pub mean_cell_area: f32,
    /// Standard deviation of the cells' areas \[cm²\] (each cell's outer ring less its holes;
    /// cells that wrap around a periodic lattice are left out).
    pub cell_area_spread: f32,
    /// Junctions: network vertices where three or more cracks meet.
    pub junctions: u32,
    /// Dead ends: cracks that end inside a cell (vertices of degree 1 off the border).
    pub dead_ends: u32,
}

impl<S: Scalar> Mud<'_, S> {
    /// The statistics of the traced network (the run's end, or the last [`Mud::trace`]).
    /// Work: a walk of the network and of every cell's boundary.
    pub fn statistics(&self) -> CrackStatistics {
        let w = self.params.element_size;
        let (_, deep) = self.factors();
        let [width, height] = self.lattice.extent().map(|e| e * deep.to_f32());
        let plate = f64::from(width) * f64::from(height);
        let mut length = 0.0f64;
        for_each_piece_length(self, |l| length += f64::from(l));
        let (mut junctions, mut dead_ends) = (0u32, 0u32);
        self.for_each_vertex(|v| match v.degree {
            1 if v.on_border == 0 => dead_ends += 1,
            d if d >= 3 => junctions += 1,
            _ => {}
        });
        let (areas, cells) = self.cell_areas();
        let cm2 = f64::from(w) * f64::from(w);
        let mean = plate / f64::from(cells.max(1));
        let spread = if areas.count > 0 {
            let m = areas.sum / areas.count as f64;
            libm::sqrt((areas.sum_squares / areas.count as f64 - m * m).max(0.0))
        } else {
            0.0
        };
        CrackStatistics {
            crack_density: (length / (plate * f64::from(w))) as f32,
            cells,
            mean_cell_area: (mean * cm2) as f32,
            cell_area_spread: (spread * cm2) as f32,
            junctions,
            dead_ends,
        }
    }
}

/// Calls `add` with the length of every straight piece of the traced network.
fn for_each_piece_length<S: Scalar>(mud: &Mud<'_, S>, mut add: impl FnMut(f32)) {
    mud.for_each_network_piece(|a, b| add(libm::hypotf(b.at[0] - a.at[0], b.at[1] - a.at[1])));
}

/// Sums over the cells' net areas (lattice units²).
pub(super) struct AreaSums {
    pub(super) count: usize,
    pub(super) sum: f64,
    pub(super) sum_squares: f64,
}
