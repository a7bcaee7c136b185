//! Tiles: a sub-rectangle of a render's image, drawn bit for bit as the whole image has it.

use super::RasterError;

/// A rectangle of an image's pixels: `width` columns from column `x`, `height` rows from row
/// `y`. A render of a tile writes `width × height` pixels, each equal, bit for bit, to the same
/// pixel of the whole image's render; so an engine can spread a large render over frames, or
/// draw only what is on screen. In C: `hibi_tile`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(C)]
pub struct Tile {
    /// First column.
    pub x: u32,
    /// First row.
    pub y: u32,
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
}

impl Tile {
    /// The whole `width × height` image.
    pub const fn whole(width: u32, height: u32) -> Tile {
        Tile { x: 0, y: 0, width, height }
    }

    /// The tile's pixel count, checked (non-zero, fits in memory).
    pub fn pixels(&self) -> Result<usize, RasterError> {
        super::pixel_count(self.width, self.height)
    }

    /// Checks that the tile is not empty and lies inside a `width × height` image.
    pub fn check_inside(&self, width: u32, height: u32) -> Result<(), RasterError> {
        let inside =
            |start: u32, length: u32, size: u32| length > 0 && start.checked_add(length).is_some_and(|end| end <= size);
        if inside(self.x, self.width, width) && inside(self.y, self.height, height) {
            Ok(())
        } else {
            Err(RasterError::Tile)
        }
    }

    /// The clip that visits the tile's pixels, grown by `margin` pixels on every side.
    pub(crate) fn clip(&self, margin: u32) -> super::Clip {
        let m = i64::from(margin);
        super::Clip {
            x: i64::from(self.x) - m,
            y: i64::from(self.y) - m,
            width: self.width + 2 * margin,
            height: self.height + 2 * margin,
        }
    }
}
