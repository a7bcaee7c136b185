//! Connected regions of a raster: the pieces of a picture that its strokes enclose.

use super::{RasterError, pixel_count};

/// Follows parents to the root, halving the path. Parents never exceed their child's index.
fn find(parent: &mut [u32], mut x: usize) -> usize {
    while parent[x] as usize != x {
        let grandparent = parent[parent[x] as usize];
        parent[x] = grandparent;
        x = grandparent as usize;
    }
    x
}

/// Joins the sets of `a` and `b`, the smaller index becoming the root.
fn union(parent: &mut [u32], a: usize, b: usize) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        let (low, high) = if ra < rb { (ra, rb) } else { (rb, ra) };
        parent[high] = low as u32;
    }
}

/// Labels the 4-connected regions of pixels where `open(pixel)` holds, wrapping around the
/// edges when `wrap` is set. `labels` gets 0, 1, ... per region (in order of each region's
/// first pixel) and `u32::MAX` for closed pixels; `sizes` (if given) is filled with each
/// region's pixel count up to its length. Returns the number of regions.
pub fn label_regions(
    width: u32,
    height: u32,
    wrap: bool,
    open: impl Fn(usize) -> bool,
    labels: &mut [u32],
) -> Result<u32, RasterError> {
    let pixels = pixel_count(width, height)?;
    if labels.len() < pixels {
        return Err(RasterError::BufferTooSmall { layer: super::Layer::Cell, needed: pixels });
    }
    let labels = &mut labels[..pixels];
    let (w, h) = (width as usize, height as usize);
    for (i, l) in labels.iter_mut().enumerate() {
        *l = i as u32;
    }
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            if !open(i) {
                continue;
            }
            let right = if x + 1 < w {
                Some(i + 1)
            } else if wrap {
                Some(y * w)
            } else {
                None
            };
            let down = if y + 1 < h {
                Some(i + w)
            } else if wrap {
                Some(x)
            } else {
                None
            };
            for j in [right, down].into_iter().flatten() {
                if open(j) {
                    union(labels, i, j);
                }
            }
        }
    }
    let mut regions = 0u32;
    for i in 0..pixels {
        if !open(i) {
            continue;
        }
        let parent = labels[i] as usize;
        labels[i] = if parent == i {
            regions += 1;
            regions - 1
        } else {
            labels[parent] // already final: parent < i
        };
    }
    for (i, l) in labels.iter_mut().enumerate() {
        if !open(i) {
            *l = u32::MAX;
        }
    }
    Ok(regions)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cross_cuts_a_torus_into_one_and_a_plane_into_four() {
        // 5×5 with a closed cross through the middle row and column.
        let closed = |i: usize| i / 5 == 2 || i % 5 == 2;
        let mut labels = [0u32; 25];
        assert_eq!(label_regions(5, 5, false, |i| !closed(i), &mut labels), Ok(4));
        assert_eq!(labels[0], 0);
        assert_eq!(labels[24], 3);
        assert_eq!(labels[12], u32::MAX);
        assert_eq!(label_regions(5, 5, true, |i| !closed(i), &mut labels), Ok(1));
        assert_eq!(
            label_regions(5, 5, true, |_| true, &mut labels[..24]),
            Err(RasterError::BufferTooSmall { layer: super::super::Layer::Cell, needed: 25 })
        );
    }
}
