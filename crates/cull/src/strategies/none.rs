//! `none`: no culling. Every pixel gets every VPL of its interleaved subregion (section 6),
//! the brute-force baseline.
use crate::lists::{assemble, pixel_count, ListChunk};
use crate::partition::Partition;
use slc_core::{CullError, CullInput, Culler, LightLists, Strategy, NO_LIST};

/// No culling: one list per subregion holding all its VPLs (ascending); every pixel with a
/// G-buffer sample shades with its subregion's list, pixels without one get none.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NoCulling;

impl Culler<CullInput<'_>> for NoCulling {
    type Lists = LightLists;
    type Error = CullError;

    fn strategy(&self) -> Strategy {
        Strategy::None
    }

    fn cull(&self, input: &CullInput) -> Result<LightLists, CullError> {
        let pixels = pixel_count(input.gbuffer)?;
        let il = input.interleaving;
        let partition = Partition::new(input.vpls, il)?;
        let width = input.gbuffer.width.max(1);
        let subregion = |p: usize| il.pixel_subregion(p as u32 % width, p as u32 / width);
        let seen: Vec<usize> = input
            .gbuffer
            .samples
            .iter()
            .enumerate()
            .filter(|(_, g)| g.is_some())
            .map(|(p, _)| p)
            .collect();
        // Lists only for the subregions some pixel shades.
        let mut used = vec![false; il.subregions() as usize];
        for &p in &seen {
            used[subregion(p) as usize] = true;
        }
        let mut chunk = ListChunk::default();
        let list_of: Vec<u32> = (0..il.subregions())
            .map(|s| {
                if used[s as usize] {
                    chunk.push_merged(partition.of(s), &[])
                } else {
                    NO_LIST
                }
            })
            .collect();
        chunk.pixels = seen
            .into_iter()
            .map(|p| (p as u32, list_of[subregion(p) as usize]))
            .collect();
        assemble(vec![chunk], pixels)
    }
}
