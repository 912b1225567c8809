//! The rank of each light list among a tile's (or pair of lists: a pixel's own and its
//! shared one), in the order the tile's pixels first meet them, found in a small hash
//! table: a tile of per-pixel lists (`binned`) has as many lists as pixels, and a search
//! through the ranks found so far made shading those tiles quadratic in their pixels.

/// One slot of the table: the list it holds and its rank, valid in the tile `generation`.
#[derive(Clone, Copy, Default)]
struct Slot {
    generation: u32,
    rank: u32,
    list: u64,
}

/// An open-addressing table from list to rank, reused from tile to tile (a new generation per
/// tile instead of clearing it).
#[derive(Default)]
pub(crate) struct ListRanks {
    slots: Vec<Slot>,
    generation: u32,
}

impl ListRanks {
    /// Forgets the previous tile's lists, with room for the lists of `pixels` pixels (at most
    /// half the slots filled).
    pub(crate) fn start(&mut self, pixels: usize) {
        let size = (2 * pixels).next_power_of_two().max(16);
        if self.slots.len() < size || self.generation == u32::MAX {
            self.slots = vec![Slot::default(); size.max(self.slots.len())];
            self.generation = 0;
        }
        self.generation += 1;
    }

    /// The rank of list (or pair of lists) `l` in this tile: its place in `lists`, where it is
    /// appended when the tile meets it first. At most the `pixels` given to [`Self::start`] lists per tile.
    #[inline]
    pub(crate) fn rank(&mut self, l: u64, lists: &mut Vec<u64>) -> u32 {
        let mask = self.slots.len() - 1;
        let mut i = (l.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 40) as usize & mask;
        loop {
            let slot = &mut self.slots[i];
            if slot.generation != self.generation {
                *slot = Slot {
                    generation: self.generation,
                    list: l,
                    rank: lists.len() as u32,
                };
                lists.push(l);
                return slot.rank;
            }
            if slot.list == l {
                return slot.rank;
            }
            i = (i + 1) & mask;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Ranks in the order lists are first met, the same rank each time a list comes back,
    /// nothing kept from one tile to the next; a full tile of distinct lists (one per pixel,
    /// numbers that collide in the table) and keys near u64::MAX.
    #[test]
    fn ranks_follow_first_appearance_per_tile() {
        let mut ranks = ListRanks::default();
        let mut lists = Vec::new();
        ranks.start(4);
        let got: Vec<u32> = [7, 3, 7, 9, 3, u64::MAX - 1]
            .iter()
            .map(|&l| ranks.rank(l, &mut lists))
            .collect();
        assert_eq!(got, [0, 1, 0, 2, 1, 3]);
        assert_eq!(lists, [7, 3, 9, u64::MAX - 1]);
        lists.clear();
        ranks.start(256);
        assert_eq!(ranks.rank(9, &mut lists), 0, "a new tile starts empty");
        // 256 distinct lists spaced so that many share a slot before probing.
        let many: Vec<u64> = (0..256).map(|i| i << 20).collect();
        lists.clear();
        ranks.start(256);
        for (i, &l) in many.iter().enumerate() {
            assert_eq!(ranks.rank(l, &mut lists), i as u32);
        }
        for (i, &l) in many.iter().enumerate().rev() {
            assert_eq!(ranks.rank(l, &mut lists), i as u32);
        }
        assert_eq!(lists, many);
    }
}
