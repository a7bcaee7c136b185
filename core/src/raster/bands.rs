//! A tile's layers cut into bands of rows: for a caller who draws one picture on several
//! threads, each band by its own `render_tile` call. The core itself stays on one thread; every
//! model draws a tile's pixels bit for bit as the whole picture has them, so the bands put
//! together are the picture one call draws.

use super::{Layers, Tile};

/// The bands of a tile's layers, top to bottom: each band's tile and its rows of every layer
/// asked for. Made by [`Layers::bands`].
pub struct Bands<'o> {
    layers: Layers<'o>,
    tile: Tile,
    rows: u32,
    done: u32,
}

/// The first `n` values of `rest` (all of it if it is shorter), leaving the others in `rest`.
fn take<'o, T>(rest: &mut Option<&'o mut [T]>, n: usize) -> Option<&'o mut [T]> {
    let whole = rest.take()?;
    let (head, tail) = whole.split_at_mut(n.min(whole.len()));
    *rest = Some(tail);
    Some(head)
}

impl<'o> Layers<'o> {
    /// These layers of `tile`, cut into bands of `rows` rows (at least one; the last band may
    /// be shorter): each band's tile and its part of every layer. The bands carry no scratch:
    /// a band that needs one gets its own, [`scratch_len`](super::scratch_len) for the band's
    /// tile. A layer shorter than the tile ends in a band whose part is short, which that
    /// band's render refuses by name.
    pub fn bands(self, tile: &Tile, rows: u32) -> Bands<'o> {
        Bands { layers: Layers { scratch: None, ..self }, tile: *tile, rows: rows.max(1), done: 0 }
    }
}

impl<'o> Iterator for Bands<'o> {
    type Item = (Tile, Layers<'o>);

    fn next(&mut self) -> Option<Self::Item> {
        if self.done >= self.tile.height {
            return None;
        }
        let height = self.rows.min(self.tile.height - self.done);
        let band = Tile { y: self.tile.y + self.done, height, ..self.tile };
        self.done += height;
        let n = band.width as usize * height as usize;
        let l = &mut self.layers;
        let layers = Layers {
            mask: take(&mut l.mask, n),
            height: take(&mut l.height, n),
            height16: take(&mut l.height16, n),
            normal: take(&mut l.normal, n),
            normal_rgb8: take(&mut l.normal_rgb8, n),
            time: take(&mut l.time, n),
            cell: take(&mut l.cell, n),
            preview: take(&mut l.preview, n),
            scratch: None,
        };
        Some((band, layers))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_cut_every_layer_by_rows() {
        let (mut mask, mut time) = ([0u8; 21], [0.0f32; 21]);
        let layers = Layers { mask: Some(&mut mask), time: Some(&mut time), ..Layers::default() };
        let tile = Tile { x: 2, y: 5, width: 3, height: 7 };
        let mut seen = 0;
        for (k, (band, layers)) in layers.bands(&tile, 3).enumerate() {
            assert_eq!(band, Tile { x: 2, y: 5 + 3 * k as u32, width: 3, height: if k == 2 { 1 } else { 3 } });
            let (m, t) = (layers.mask.unwrap(), layers.time.unwrap());
            assert_eq!((m.len(), t.len()), (3 * band.height as usize, 3 * band.height as usize));
            assert!(layers.height.is_none() && layers.scratch.is_none());
            m.fill(k as u8 + 1);
            t.fill(k as f32);
            seen += 1;
        }
        assert_eq!(seen, 3);
        assert_eq!(mask, [1, 1, 1, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2, 2, 2, 2, 2, 3, 3, 3]);
        assert_eq!(time[20], 2.0);
        // Zero rows are one; a short layer ends short.
        let mut short = [0u8; 4];
        let mut lengths = [usize::MAX; 8];
        let short = Layers { mask: Some(&mut short), ..Layers::default() };
        for (k, (_, l)) in short.bands(&tile, 0).enumerate() {
            lengths[k] = l.mask.map_or(0, |m| m.len());
        }
        assert_eq!(lengths, [3, 1, 0, 0, 0, 0, 0, usize::MAX]);
    }
}
