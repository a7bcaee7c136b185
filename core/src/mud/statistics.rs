//! Crack statistics measured on the traced network and its cells (see [`super::network`] and
//! [`super::cells`]), independent of any drawing.

use super::Mud;
use crate::scalar::Scalar;

/// How far along each crack its course from a junction is measured [lattice spacings]: far
/// enough that a crack's zigzag through the mesh cells averages out.
pub const JUNCTION_REACH: f32 = 3.0;

/// The widest angle between neighbouring directions of `arms` (at most four), in degrees.
fn widest_angle(arms: &[[f32; 2]]) -> f32 {
    let mut angles = [0.0f32; 4];
    let n = arms.len().min(4);
    for (angle, arm) in angles.iter_mut().zip(arms) {
        *angle = libm::atan2f(arm[1], arm[0]);
    }
    let angles = &mut angles[..n];
    angles.sort_unstable_by(f32::total_cmp);
    let mut widest = 0.0f32;
    for i in 0..n {
        let next = if i + 1 < n { angles[i + 1] } else { angles[0] + core::f32::consts::TAU };
        widest = widest.max(next - angles[i]);
    }
    widest.to_degrees()
}

/// Crack statistics of a run's traced network.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CrackStatistics {
    /// Crack length per area [1/cm]: the network's length (its edges' polylines, branches
    /// included) over the plate's area. The figures in cm saturate at `f32::MAX` for elements
    /// so large or small that they would pass it.
    pub crack_density: f32,
    /// Cells: the regions the separating cracks enclose (outer rings), wrapping ones included.
    pub cells: u32,
    /// Mean area of a cell \[cm²\]: the plate's area over the number of cells.
    pub mean_cell_area: f32,
    /// Standard deviation of the cells' areas \[cm²\] over their outer rings; holes (islands,
    /// rare) are taken off all cells evenly, and cells that wrap around a periodic lattice
    /// are left out.
    pub cell_area_spread: f32,
    /// Junctions: network vertices where three or more cracks meet.
    pub junctions: u32,
    /// T junctions: those where one crack runs on and another meets it, i.e. two of the
    /// cracks' courses (see [`JUNCTION_REACH`]) are within 30° of a straight line (the widest
    /// angle between neighbouring courses is at least 150°). The rest are Y junctions.
    pub t_junctions: u32,
    /// The mean over junctions of the widest angle between neighbouring cracks' courses
    /// \[degrees\]: 180 for a perfect T, 120 for a symmetric Y.
    pub mean_widest_junction_angle: f32,
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
        let (mut t_junctions, mut widest_sum, mut measured) = (0u32, 0.0f64, 0u32);
        self.for_each_junction(JUNCTION_REACH, |arms| {
            let widest = widest_angle(arms);
            measured += 1;
            widest_sum += f64::from(widest);
            if widest >= 150.0 {
                t_junctions += 1;
            }
        });
        let (areas, cells) = self.cell_areas();
        let cm2 = f64::from(w) * f64::from(w);
        let mean = plate / f64::from(cells.max(1));
        let spread = if areas.count > 0 {
            let m = areas.sum / areas.count as f64;
            crate::scalar::sqrt((areas.sum_squares / areas.count as f64 - m * m).max(0.0))
        } else {
            0.0
        };
        // In cm, a plate of huge or tiny elements can pass f32's range: the figures saturate.
        let saturating = |x: f64| x.min(f64::from(f32::MAX)) as f32;
        CrackStatistics {
            crack_density: saturating(length / (plate * f64::from(w))),
            cells,
            mean_cell_area: saturating(mean * cm2),
            cell_area_spread: saturating(spread * cm2),
            junctions,
            t_junctions,
            mean_widest_junction_angle: if measured > 0 { (widest_sum / f64::from(measured)) as f32 } else { 0.0 },
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn widest_angles_tell_t_from_y() {
        let t = widest_angle(&[[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0]]);
        assert!((t - 180.0).abs() < 1e-3, "{t}");
        let y = widest_angle(&[[1.0, 0.0], [-0.5, 0.866_025_4], [-0.5, -0.866_025_4]]);
        assert!((y - 120.0).abs() < 1e-3, "{y}");
        // Order does not matter, and the gap across ±180° counts.
        let wrapped = widest_angle(&[[-1.0, 0.01], [-1.0, -0.01], [1.0, 0.0]]);
        assert!((wrapped - 180.0).abs() < 1.0, "{wrapped}");
    }
}
