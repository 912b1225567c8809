//! `#[repr(C)]` twins of the WGSL structs of the culling passes every layout shares (bounds, partition, tile frusta). Each names the WGSL module whose struct
//! of the same name must keep the same fields in the same order, a compile-time check holds its
//! size, and a unit test compares it with the layout naga computes from the linked kernel. Only
//! 4-byte scalars and `[f32; 4]` / `[u32; 4]` are used (WGSL `f32`, `u32`, `vec4<f32>`,
//! `vec4<u32>`), never vec3, so the Rust and WGSL layouts agree without hidden padding.
use bytemuck::{Pod, Zeroable};

/// `GpuView::glossy`: the bound of glossy VPLs ([`slc_core::GlossyBound`]).
pub const GLOSSY_SPHERE: u32 = 0;
pub const GLOSSY_ENCLOSING_SPHERE: u32 = 1;
pub const GLOSSY_ELLIPSOID: u32 = 2;
/// The culling view of `slc_cull::view` (x right, y down, z forward) and the bound
/// parameters. Keep in sync with `View` in `bounds.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuView {
    /// Columns of the world-to-view rotation R ([`slc_cull::CullView::rotation`]).
    pub rotation: [[f32; 4]; 3],
    /// The eye (camera position), subtracted before rotating: `R (p − eye)`.
    pub eye: [f32; 4],
    /// δ of eq. (2).
    pub delta: f32,
    /// [`GLOSSY_SPHERE`], [`GLOSSY_ENCLOSING_SPHERE`] or [`GLOSSY_ELLIPSOID`].
    pub glossy: u32,
    /// Number of VPLs.
    pub count: u32,
    /// Relative growth of radii and semi-axes (`slc_cull`'s `BOUND_SLACK`, 1e-3).
    pub slack: f32,
    /// Interleaving factor K and seed ([`slc_core::Interleaving`]): each bound records its VPL's
    /// subregion.
    pub k: u32,
    pub seed: u32,
    /// 1 where each VPL's `GpuBoxBound` is written too (`GlossyBound::Tight`), else 0.
    pub box_bounds: u32,
    /// 1 where each VPL's `GpuBoundShape` is written too (the raster baselines), else 0.
    pub shapes: u32,
    /// 1 where each VPL's [`GpuLocalBound`] is written too (the binned strategy), else 0.
    pub locals: u32,
    pub pad: [u32; 3],
}
const _: () = assert!(std::mem::size_of::<GpuView>() == 112);
/// Largest interleaving factor K (as `slc_cull`): K² subregions fit easily in u32.
pub const MAX_K: u32 = 1024;
/// [`slc_cull::BOUND_SLACK`] in f32: radii and semi-axes grow by this relative amount so f32
/// rounding never culls a contributing VPL.
pub const BOUND_SLACK: f32 = slc_cull::BOUND_SLACK as f32;
/// `GpuBound::kind`.
pub const BOUND_EMPTY: u32 = 0;
pub const BOUND_SPHERE: u32 = 1;
pub const BOUND_ELLIPSOID: u32 = 2;
/// A bound that does not fit in f32 (the CPU's `BoundsError::Overflow`).
pub const BOUND_OVERFLOW: u32 = 3;
/// One VPL's bound in the culling view. Keep in sync with `Bound` in `bound.wesl`.
///
/// - [`BOUND_SPHERE`]: `center` = view-space centre (xyz) and squared radius (w); `bs` zero.
/// - [`BOUND_ELLIPSOID`]: `bs` = the columns of BS (eq. 16-17, section 5.2), `center` = BS·c
///   (xyz) and 1 (w): in that space the ellipsoid is the unit ball around BS·c.
/// - [`BOUND_EMPTY`]: nothing reflected (zero flux, ωi·n <= 0); never listed.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuBound {
    pub bs: [[f32; 4]; 3],
    pub center: [f32; 4],
    pub kind: u32,
    /// The VPL's index in the input.
    pub index: u32,
    /// The VPL's interleaved subregion, `Interleaving::vpl_subregion(id)` (section 6).
    pub subregion: u32,
    pub pad: u32,
}
const _: () = assert!(std::mem::size_of::<GpuBound>() == 80);
/// One VPL's bound in world axes relative to its position q, as `bounds.wesl` forms it (the
/// sphere of section 6 or the GGX spheroid of eq. 12-15, grown by [`BOUND_SLACK`]): the
/// `binned` strategy tests each pixel's offset x − q against it, as the shader forms that
/// offset (`cull::binned`). Keep in sync with `LocalBound` in `bounds.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuLocalBound {
    /// The centre c − q (xyz) and the semi-axis along the axis (w; 0: no bound).
    pub center_along: [f32; 4],
    /// The unit axis (xyz: ω_u of eq. 14 for a spheroid) and the semi-axis across it (w).
    pub axis_across: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuLocalBound>() == 32);
/// Interleaved-subregion tiles and the culling view for the tile passes. Keep in sync with
/// `CullParams` in `tile_depth.wesl` and `tiled_cull.wesl`.
///
/// Tiles form a uniform grid per subregion (paper supplemental Listing 2): every one of the
/// K² subregions gets `tiles_x` x `tiles_y` tiles of 16 x 16 pixels of its subregion image,
/// sized for the largest subregion; tile t is tile `t mod (tiles_x tiles_y)` (row-major) of
/// subregion `t div (tiles_x tiles_y)`. Tiles past a smaller subregion's edge have no pixels.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuCullParams {
    /// Columns of the world-to-view rotation R ([`slc_cull::CullView::rotation`]).
    pub rotation: [[f32; 4]; 3],
    /// The eye (camera position).
    pub eye: [f32; 4],
    /// Image-plane half extents at unit depth (aspect tan(yfov/2), tan(yfov/2)) and the image
    /// size (W, H) as floats.
    pub image: [f32; 4],
    pub width: u32,
    pub height: u32,
    /// Interleaving factor K.
    pub k: u32,
    pub tiles_x: u32,
    pub tiles_y: u32,
    pub tile_count: u32,
    pub vpl_count: u32,
    /// `slc_cull`'s `FRUSTUM_SLACK` (1e-6): growth of the tile rectangle and depth ranges.
    pub frustum_slack: f32,
    /// [`CULL_COUNT`] or [`CULL_WRITE`].
    pub mode: u32,
    pub pad: [u32; 3],
}
const _: () = assert!(std::mem::size_of::<GpuCullParams>() == 128);
/// `GpuCullParams::mode`: count each tile's list entries, or write the lists.
pub const CULL_COUNT: u32 = 0;
pub const CULL_WRITE: u32 = 1;
/// [`slc_cull::FRUSTUM_SLACK`] in f32: growth of the tile rectangle and depth ranges.
pub const FRUSTUM_SLACK: f32 = slc_cull::FRUSTUM_SLACK as f32;
/// One tile's frusta after Modified HalfZ (section 5.1): the image-plane rectangle at unit
/// depth and the depth ranges of its near and far clusters, all grown by the frustum
/// slack. Keep in sync with `TileFrusta` in `tile_depth.wesl` and
/// `tiled_cull.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuTileFrusta {
    /// (u0, v0, u1, v1).
    pub rect: [f32; 4],
    /// Near cluster [z0, z1] (xy), far cluster [z0, z1] (zw).
    pub ranges: [f32; 4],
    /// Cluster mask (x: bit 0 near, bit 1 far; 0 = no sample in the tile); the range of the
    /// tile's subregion's VPLs in the partition's order (y..z); unused (w).
    pub info: [u32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuTileFrusta>() == 48);
/// The fault and total record the tile passes write. Keep in sync with the `status` arrays of
/// `tile_depth.wesl`, `tiled_cull.wesl` and `scan.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuCullStatus {
    /// Smallest pixel whose sample is not in front of the camera (`u32::MAX`: none).
    pub bad_pixel: u32,
    /// Smallest VPL whose bound overflowed f32 (`u32::MAX`: none).
    pub overflow_vpl: u32,
    /// Total list entries (the scan's sum).
    pub total: u32,
    /// 1 if the total overflowed u32.
    pub total_overflow: u32,
}
const _: () = assert!(std::mem::size_of::<GpuCullStatus>() == 16);
impl GpuCullStatus {
    /// The initial record: no faults, no entries.
    pub const CLEAR: Self = Self {
        bad_pixel: u32::MAX,
        overflow_vpl: u32::MAX,
        total: 0,
        total_overflow: 0,
    };
}
/// Parameters of the subregion partition (`partition.wesl`, `PartitionParams`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuPartitionParams {
    pub vpl_count: u32,
    /// K².
    pub subregions: u32,
    /// [`CULL_COUNT`] or [`CULL_WRITE`].
    pub mode: u32,
    /// The VPLs are split into `chunks` runs of `chunk` (a multiple of 256): one workgroup
    /// per run.
    pub chunks: u32,
    pub chunk: u32,
    pub pad: [u32; 3],
}
const _: () = assert!(std::mem::size_of::<GpuPartitionParams>() == 32);
/// One VPL's bound of p(ωo, l) of eq. (2) over boxes of receivers (`slc_bounds::BoxBound`,
/// docs/tight-bounds.md) in the culling view, written by `bounds.wesl` for the tight
/// strategies. Keep in sync with `BoxBound` in `box_bound.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuBoxBound {
    /// q = R (position − eye) (xyz) and the growth of every box tested against this VPL for
    /// the f32 rounding of q, of the receivers' view positions and of the shader's offsets
    /// x − q (w).
    pub q_slack: [f32; 4],
    /// The lobe's normal in view (xyz) and the largest intensity in any direction (w).
    pub normal_peak: [f32; 4],
    /// ωi (xyz) and cos θh_max(ωi) of supplemental eq. (2) (w).
    pub omega_i_cos_h_max: [f32; 4],
    /// The mirror direction ω_u (xyz) and G1(ωi)/(4 ωi·n) (w).
    pub omega_u_g1_i: [f32; 4],
    /// Φ times `GlossyLobe::bound_factor` (xyz) and α (w, the lobe's largest).
    pub flux_alpha: [f32; 4],
    /// Schlick's F0 (xyz) and a dielectric's η (w).
    pub f0_eta: [f32; 4],
    /// [`BOX_EMPTY`], [`BOX_DIFFUSE`] or [`BOX_GLOSSY`]; the Fresnel model; the bits of the
    /// α whose G1 bounds G1(ωo) (0.0: bounded by 1, a tilted normal); the bits of
    /// δ ξ / (1 + `PROBABILITY_SLACK`).
    pub info: [u32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuBoxBound>() == 112);
/// `GpuBoxBound::info[0]`: never listed, a diffuse lobe (eq. 4, f = kd/π), a glossy one.
pub const BOX_EMPTY: u32 = 0;
pub const BOX_DIFFUSE: u32 = 1;
pub const BOX_GLOSSY: u32 = 2;

#[cfg(test)]
mod tests {
    use super::*;

    wgsl_twins! {
        crate::cull::bounds::SOURCE => {
            GpuView as "View",
            GpuBound as "Bound",
            GpuLocalBound as "LocalBound",
            GpuBoxBound as "BoxBound",
        }
        crate::cull::tiled::depth::SOURCE => {
            GpuCullParams as "CullParams",
            GpuTileFrusta as "TileFrusta",
        }
        crate::cull::tiled::SOURCE => {
            GpuCullParams as "CullParams",
            GpuBound as "Bound",
        }
        crate::cull::partition::SOURCE => {
            GpuPartitionParams as "PartitionParams",
        }
        crate::cull::tight::SOURCE => {
            GpuBoxBound as "BoxBound",
        }
    }
}
