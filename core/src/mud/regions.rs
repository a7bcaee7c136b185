//! The cells the cracks enclose, as the picture shows them.
//!
//! On the lattice, a straight crack perpendicular to one spring family breaks that family
//! only: the springs of the other two families cross the crack at 60° and are stretched half
//! as much, so they survive as bridges, and Fig. 5 draws such a crack as dashes whose gaps
//! (one bridge, 1/√3 spacing) the eye closes. The enclosed cells are therefore measured on
//! the drawn network: the crack-free regions of a mask drawn with strokes
//! [`CELL_STROKE_WIDTH`] spacings wide (enough to close the bridge gaps), 4 pixels per
//! spacing, wrapping on periodic lattices. Regions smaller than one element are corners of
//! crack junctions, not cells, and are not counted.

use super::render::MudRender;
use super::{Boundary, Mud, MudError};
use crate::raster::{RasterError, label_regions};
use crate::scalar::Scalar;

/// Stroke width, in lattice spacings, of the mask the cells are measured on.
pub const CELL_STROKE_WIDTH: f32 = 0.6;

/// Pixels per lattice spacing of the mask the cells are measured on.
const PIXELS_PER_SPACING: u32 = 4;

/// Crack statistics of a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrackStatistics {
    /// Crack length per area [1/cm]: broken faces over the area.
    pub crack_density: f32,
    /// Cells enclosed by the drawn crack network.
    pub cells: u32,
    /// Mean area of a cell \[cm²\]: the lattice's area over the number of cells.
    pub mean_cell_area: f32,
}

impl<S: Scalar> Mud<'_, S> {
    /// The raster [`Mud::statistics`] measures cells on.
    fn cell_raster(&self) -> MudRender {
        MudRender {
            width: self.lattice.columns * PIXELS_PER_SPACING,
            height: self.lattice.rows * PIXELS_PER_SPACING,
            width_scale: 0.0,
            min_width: CELL_STROKE_WIDTH * PIXELS_PER_SPACING as f32,
            groove_depth: 0.0,
            offset: [0.0; 2],
        }
    }

    /// Scratch pixels [`Mud::statistics`] needs (both buffers).
    pub fn statistics_pixels(&self) -> usize {
        let r = self.cell_raster();
        r.width as usize * r.height as usize
    }

    /// Crack density and the cells the drawn crack network encloses; `mask` and `labels` are
    /// scratch of [`Mud::statistics_pixels`] elements each (left holding the mask and each
    /// pixel's cell label). Nothing is written if either is shorter.
    pub fn statistics(&self, mask: &mut [u8], labels: &mut [u32]) -> Result<CrackStatistics, MudError> {
        let raster = self.cell_raster();
        let pixels = self.statistics_pixels();
        if mask.len() < pixels || labels.len() < pixels {
            return Err(MudError::BufferTooSmall { needed: pixels });
        }
        let to_mud = |e: RasterError| match e {
            RasterError::BufferTooSmall { needed } => MudError::BufferTooSmall { needed },
            _ => MudError::BufferTooSmall { needed: pixels },
        };
        self.render_mask(&raster, mask).map_err(to_mud)?;
        let wrap = self.params.boundary == Boundary::Periodic;
        let regions = label_regions(raster.width, raster.height, wrap, |i| mask[i] < 128, labels).map_err(to_mud)?;
        // Count the regions of at least one element's area.
        let element_pixels = self.lattice.element_area() * (PIXELS_PER_SPACING * PIXELS_PER_SPACING) as f32;
        let mut cells = 0u32;
        let mut first = 0usize;
        for region in 0..regions {
            // Regions are labelled in order of their first pixel; count each one's pixels.
            while labels[first] != region {
                first += 1;
            }
            let size = labels[first..pixels].iter().filter(|&&l| l == region).count();
            if size as f32 >= element_pixels {
                cells += 1;
            }
        }
        let w = self.params.element_size;
        let area = self.lattice.node_count() as f32 * self.lattice.element_area() * w * w;
        Ok(CrackStatistics { crack_density: self.crack_density(), cells, mean_cell_area: area / cells.max(1) as f32 })
    }
}
