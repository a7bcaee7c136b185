//! Edges built once for two cells. A bisector edge between two cells of a level (paper §4.1
//! (2): split where the parent's outline crosses it, then perturbed) is a function of data
//! both cells share, computed in the frame and direction of the lower site id. The cell built
//! first keeps the edge's inner points here; its neighbour, built soon after (siblings are
//! built one after another), takes them instead of computing them again. Keeping is only a
//! shortcut: a neighbour that finds nothing computes the same points itself.

/// Inner points one kept edge can hold (perturbation depth 2 with no crossing: the finer
/// levels, where nearly all edges are).
pub(super) const KEPT_POINTS: usize = 3;
/// Edges kept per level.
pub(super) const SLOTS: usize = 16;

/// What identifies an edge from both sides: the two sites' ids, lower first, the higher one's
/// periodic image relative to the lower's, and the edge's ends relative to the lower's image,
/// in the direction the lower one runs it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct EdgeKey {
    pub(super) ids: [u32; 2],
    pub(super) offset: [i32; 2],
    pub(super) ends: [[i64; 2]; 2],
}

impl EdgeKey {
    /// The key folded into a word, never 0.
    fn tag(&self) -> u64 {
        let [[a, b], [c, d]] = self.ends;
        let ids = u64::from(self.ids[0]) << 32 | u64::from(self.ids[1]);
        let offset = u64::from(self.offset[0] as u32) << 32 | u64::from(self.offset[1] as u32);
        (ids ^ offset.rotate_left(16)
            ^ (a as u64)
            ^ (b as u64).rotate_left(13)
            ^ (c as u64).rotate_left(29)
            ^ (d as u64).rotate_left(43))
            | 1
    }
}

/// One kept edge: its key and its inner points (relative to the lower site's image, in its
/// direction).
#[derive(Clone, Copy, Default)]
struct Kept {
    key: EdgeKey,
    count: u8,
    /// Whether the slot holds an edge not yet taken (its tag is then not 0: the search
    /// compares tags, the fallback for a shared tag reads this).
    valid: bool,
    points: [[i64; 2]; KEPT_POINTS],
}

/// The edges kept for the neighbours still to be built, on one level (each level keeps its
/// own: a level's siblings are built between the cells of finer levels).
#[derive(Clone)]
pub(super) struct SharedEdges {
    kept: [Kept; SLOTS],
    /// Each slot's key folded into a word ([`EdgeKey::tag`]), 0 where the slot is free: the
    /// slots are searched by these, side by side.
    tags: [u64; SLOTS],
    /// The slot overwritten next when none is free.
    next: usize,
}

impl SharedEdges {
    pub(super) fn new() -> SharedEdges {
        SharedEdges { kept: [Kept::default(); SLOTS], tags: [0; SLOTS], next: 0 }
    }

    /// Frees every slot, in place (as [`SharedEdges::new`] leaves them).
    pub(super) fn clear(&mut self) {
        for (kept, tag) in self.kept.iter_mut().zip(&mut self.tags) {
            kept.valid = false;
            *tag = 0;
        }
        self.next = 0;
    }

    /// The inner points kept for `key` (each edge is taken once: it has two sides).
    pub(super) fn take(&mut self, key: &EdgeKey) -> Option<([[i64; 2]; KEPT_POINTS], usize)> {
        // The last slot with the key's tag, without branches (which slot holds the edge, if
        // any, follows no pattern a processor could learn); then the key itself, and every
        // slot should two keys share a tag.
        let tag = key.tag();
        let mut found = SLOTS;
        for (i, &t) in self.tags.iter().enumerate() {
            found = if t == tag { i } else { found };
        }
        let slot = match self.kept.get(found) {
            Some(k) if k.key == *key => found,
            Some(_) => self.kept.iter().position(|k| k.valid && k.key == *key)?,
            None => return None,
        };
        let kept = &mut self.kept[slot];
        kept.valid = false;
        self.tags[slot] = 0;
        Some((kept.points, usize::from(kept.count)))
    }

    /// Keeps `points` for `key`, in a free slot or over the oldest-written one.
    pub(super) fn keep(&mut self, key: EdgeKey, points: &[[i64; 2]]) {
        if points.len() > KEPT_POINTS {
            return;
        }
        // (A slot is free where its tag is 0.)
        let slot = match self.tags.iter().position(|&t| t == 0) {
            Some(free) => free,
            None => {
                let s = self.next;
                self.next = (s + 1) % SLOTS;
                s
            }
        };
        // (In place: the points past `count` are never read.)
        let kept = &mut self.kept[slot];
        (kept.key, kept.count, kept.valid) = (key, points.len() as u8, true);
        kept.points[..points.len()].copy_from_slice(points);
        self.tags[slot] = key.tag();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_sharing_a_tag_each_find_their_own_points() {
        // Ids (0, 0) and (0, 1) fold to the same tag.
        let key = |id: u32| EdgeKey { ids: [0, id], ..EdgeKey::default() };
        assert_eq!(key(0).tag(), key(1).tag());
        let (mut shared, other) = (SharedEdges::new(), SharedEdges::new());
        shared.keep(key(0), &[[1, 2]]);
        shared.keep(key(1), &[[3, 4], [5, 6]]);
        assert!(other.clone().take(&key(0)).is_none(), "another level");
        let (points, count) = shared.take(&key(0)).expect("kept");
        assert_eq!(&points[..count], &[[1, 2]]);
        assert!(shared.take(&key(0)).is_none(), "taken once");
        let (points, count) = shared.take(&key(1)).expect("kept");
        assert_eq!(&points[..count], &[[3, 4], [5, 6]]);
    }
}
