//! `#[repr(C)]` structs shared with the WGSL shaders. Each names the WGSL file whose struct
//! of the same name must keep the same fields in the same order, and a compile-time check
//! holds its size to the WGSL layout. Only 4-byte scalars and `[f32; 4]` / `[u32; 4]` are
//! used (WGSL `f32`, `u32`, `vec4<f32>`, `vec4<u32>`), never vec3, so the Rust and WGSL
//! layouts agree without hidden padding.
use crate::bounds_pass::BoundsSettings;
use crate::context::GpuError;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use slc_bounds::shading_normal::flux_scale;
use slc_bounds::{Anisotropy, Brdf, Fresnel, StochasticParams};
use slc_core::{GSample, Vpl, VplLobe};
use slc_cull::{CullView, GlossyBound};

/// Parameters of the RNG conformance pass. Keep in sync with `RngParams` in
/// `shaders/rng_eval.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct RngParams {
    pub seed: u32,
    pub stream: u32,
    pub counter: u32,
    /// Interleaving factor K (K x K subregions).
    pub k: u32,
    pub count: u32,
    pub pad: [u32; 3],
}
const _: () = assert!(std::mem::size_of::<RngParams>() == 32);

/// What the RNG pass writes per index i. Keep in sync with `RngSample` in
/// `shaders/rng_eval.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct RngSample {
    /// `pcg_hash(i ^ seed)`.
    pub pcg: u32,
    /// `hash4(seed, i, stream, counter)`.
    pub hash: u32,
    /// The bits of `uniform(seed, i, stream, counter)`.
    pub uniform_bits: u32,
    /// `Interleaving { k, seed }.vpl_subregion(i)`.
    pub subregion: u32,
}
const _: () = assert!(std::mem::size_of::<RngSample>() == 16);

/// `GpuVpl::info[0]`: the VPL's lobe.
pub const LOBE_DIFFUSE: u32 = 0;
pub const LOBE_GLOSSY: u32 = 1;
/// `GpuVpl::info[1]`: the Fresnel model of eq. (6) (supplemental eq. 1 or 3-5).
pub const FRESNEL_SCHLICK: u32 = 0;
pub const FRESNEL_DIELECTRIC: u32 = 1;

/// A VPL ([`slc_core::Vpl`]) as the shaders read it. Keep in sync with `Vpl` in
/// `shaders/gvpl.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuVpl {
    /// Position q (xyz) and the Russian-roulette number ξ of eq. (3) (w).
    pub position_xi: [f32; 4],
    /// Normal n (xyz) and GGX roughness α (w).
    pub normal_alpha: [f32; 4],
    /// Incoming direction ωi (xyz) and the relative index η of a dielectric Fresnel (w).
    pub omega_i_eta: [f32; 4],
    /// RGB flux Φ (xyz).
    pub flux: [f32; 4],
    /// Diffuse reflectance kd (xyz).
    pub kd: [f32; 4],
    /// Schlick F0 (xyz).
    pub f0: [f32; 4],
    /// Lobe ([`LOBE_DIFFUSE`], [`LOBE_GLOSSY`]), Fresnel model ([`FRESNEL_SCHLICK`],
    /// [`FRESNEL_DIELECTRIC`]), VPL id, unused.
    pub info: [u32; 4],
    /// The geometric normal n_g (xyz) and the bound factor (w): `flux_scale` of
    /// `slc_bounds::shading_normal` for a diffuse VPL, `GlossyLobe::bound_factor` for a
    /// glossy one (tilted shading normal, anisotropy), 1 where neither applies.
    pub geometric_tilt: [f32; 4],
    /// The anisotropy's tangent (xyz) and α_t (w), zero where the lobe is isotropic
    /// (`slc_bounds::Anisotropy`).
    pub anisotropy: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuVpl>() == 144);

fn vec4(v: Vec3, w: f32) -> [f32; 4] {
    [v.x, v.y, v.z, w]
}

/// An anisotropy as the shaders store it: the tangent (xyz) and α_t (w); zero if isotropic.
pub fn gpu_anisotropy(a: Option<Anisotropy>) -> [f32; 4] {
    a.map_or([0.0; 4], |a| vec4(a.tangent, a.alpha_t))
}

/// The anisotropy of [`gpu_anisotropy`]'s form (α_t = 0: isotropic).
pub fn anisotropy_from_gpu(a: [f32; 4]) -> Option<Anisotropy> {
    (a[3] > 0.0).then(|| Anisotropy {
        tangent: Vec3::new(a[0], a[1], a[2]),
        alpha_t: a[3],
    })
}

impl GpuVpl {
    /// Packs VPL `index` after validating it exactly as the CPU culler does
    /// (`slc_cull`'s `VplBound::new`): finite position and ωi, δ and ξ valid for eq. (2)-(3),
    /// and a valid lobe (unit normal, α in (0, 1], non-negative flux, valid Fresnel); a diffuse
    /// VPL lit from below (ωi·n <= 0) is accepted without the lobe checks, its bound is empty.
    pub fn new(vpl: &Vpl, index: usize, delta: f32) -> Result<Self, GpuError> {
        let invalid = |e: &dyn std::fmt::Display| GpuError::Input(format!("VPL {index}: {e}"));
        if !(vpl.position.is_finite() && vpl.omega_i.is_finite()) {
            return Err(GpuError::Input(format!(
                "VPL {index} has a non-finite position or incoming direction"
            )));
        }
        StochasticParams::new(delta, vpl.xi).map_err(|e| invalid(&e))?;
        let (lobe, tilt) = match vpl.lobe {
            VplLobe::Diffuse => {
                if vpl.normal.dot(vpl.omega_i) > 0.0 {
                    vpl.diffuse_lobe().map_err(|e| invalid(&e))?;
                }
                let scale = flux_scale(vpl.normal, vpl.geometric_normal, vpl.omega_i);
                (LOBE_DIFFUSE, scale)
            }
            VplLobe::Glossy => {
                let lobe = vpl.glossy_lobe().map_err(|e| invalid(&e))?;
                (LOBE_GLOSSY, lobe.bound_factor())
            }
        };
        let (fresnel, f0, eta) = match vpl.brdf.fresnel {
            Fresnel::Schlick(f0) => (FRESNEL_SCHLICK, f0, 0.0),
            Fresnel::Dielectric(eta) => (FRESNEL_DIELECTRIC, Vec3::ZERO, eta),
        };
        Ok(Self {
            position_xi: vec4(vpl.position, vpl.xi),
            normal_alpha: vec4(vpl.normal, vpl.brdf.alpha),
            omega_i_eta: vec4(vpl.omega_i, eta),
            flux: vec4(vpl.flux, 0.0),
            kd: vec4(vpl.brdf.kd, 0.0),
            f0: vec4(f0, 0.0),
            info: [lobe, fresnel, vpl.id, 0],
            geometric_tilt: vec4(vpl.geometric_normal, tilt),
            anisotropy: gpu_anisotropy(vpl.brdf.anisotropy),
        })
    }
}

/// `GpuView::glossy`: the bound of glossy VPLs ([`GlossyBound`]).
pub const GLOSSY_SPHERE: u32 = 0;
pub const GLOSSY_ENCLOSING_SPHERE: u32 = 1;
pub const GLOSSY_ELLIPSOID: u32 = 2;

/// The culling view of `slc_cull::view` (x right, y down, z forward) and the bound
/// parameters. Keep in sync with `View` in `shaders/bounds.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuView {
    /// Columns of the world-to-view rotation R ([`CullView::rotation`]).
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
}
const _: () = assert!(std::mem::size_of::<GpuView>() == 96);

/// Largest interleaving factor K (as `slc_cull`): K² subregions fit easily in u32.
pub const MAX_K: u32 = 1024;

/// [`slc_cull::BOUND_SLACK`] in f32: radii and semi-axes grow by this relative amount so f32
/// rounding never culls a contributing VPL.
pub const BOUND_SLACK: f32 = slc_cull::BOUND_SLACK as f32;

impl GpuView {
    /// The view of `settings` for `count` VPLs (the camera validated by [`CullView::new`]).
    pub fn new(settings: &BoundsSettings, count: u32) -> Result<Self, GpuError> {
        if !(1..=MAX_K).contains(&settings.interleaving.k) {
            return Err(GpuError::Input(format!(
                "interleaving factor K = {} must lie in 1..={MAX_K}",
                settings.interleaving.k
            )));
        }
        let view = CullView::new(settings.camera, settings.width, settings.height)
            .map_err(|e| GpuError::Input(e.to_string()))?;
        let r = view.rotation();
        Ok(Self {
            rotation: [
                vec4(r.x_axis, 0.0),
                vec4(r.y_axis, 0.0),
                vec4(r.z_axis, 0.0),
            ],
            eye: vec4(settings.camera.position, 0.0),
            delta: settings.delta,
            glossy: match settings.glossy {
                GlossyBound::Sphere => GLOSSY_SPHERE,
                GlossyBound::EnclosingSphere => GLOSSY_ENCLOSING_SPHERE,
                // The tight strategies cull with the spheroid first (`tight_cull_pass`).
                GlossyBound::Ellipsoid | GlossyBound::Tight => GLOSSY_ELLIPSOID,
            },
            count,
            slack: BOUND_SLACK,
            k: settings.interleaving.k,
            seed: settings.interleaving.seed,
            box_bounds: u32::from(settings.glossy == GlossyBound::Tight),
            shapes: u32::from(settings.shapes),
        })
    }
}

/// `GpuBound::kind`.
pub const BOUND_EMPTY: u32 = 0;
pub const BOUND_SPHERE: u32 = 1;
pub const BOUND_ELLIPSOID: u32 = 2;
/// A bound that does not fit in f32 (the CPU's `BoundsError::Overflow`).
pub const BOUND_OVERFLOW: u32 = 3;

/// One VPL's bound in the culling view. Keep in sync with `Bound` in `shaders/bound.wgsl`.
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

/// Interleaved-subregion tiles and the culling view for the tile passes. Keep in sync with
/// `CullParams` in `shaders/tile_depth.wgsl` and `shaders/tiled_cull.wgsl`.
///
/// Tiles form a uniform grid per subregion (paper supplemental Listing 2): every one of the
/// K² subregions gets `tiles_x` x `tiles_y` tiles of 16 x 16 pixels of its subregion image,
/// sized for the largest subregion; tile t is tile `t mod (tiles_x tiles_y)` (row-major) of
/// subregion `t div (tiles_x tiles_y)`. Tiles past a smaller subregion's edge have no pixels.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuCullParams {
    /// Columns of the world-to-view rotation R ([`CullView::rotation`]).
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
/// slack. Keep in sync with `TileFrusta` in `shaders/tile_depth.wgsl` and
/// `shaders/tiled_cull.wgsl`.
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
/// `shaders/tile_depth.wgsl`, `shaders/tiled_cull.wgsl` and `shaders/scan.wgsl`.
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

/// Parameters of the exclusive scan (`shaders/scan.wgsl`, `ScanParams`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuScanParams {
    /// Number of values; the scan writes n + 1 offsets (the last is the total).
    pub count: u32,
    pub pad: [u32; 3],
}
const _: () = assert!(std::mem::size_of::<GpuScanParams>() == 16);

/// Parameters of the subregion partition (`shaders/partition.wgsl`, `PartitionParams`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuPartitionParams {
    pub vpl_count: u32,
    /// K².
    pub subregions: u32,
    /// [`CULL_COUNT`] or [`CULL_WRITE`].
    pub mode: u32,
    pub pad: u32,
}
const _: () = assert!(std::mem::size_of::<GpuPartitionParams>() == 16);

/// `GpuSample::present`: whether the pixel holds a G-buffer sample (0: empty, e.g. sky).
/// `GpuSample::flags`: bit 0 set where the pixel has a sample, bit 1 for a dielectric Fresnel.
pub const SAMPLE_EMPTY: u32 = 0;
pub const SAMPLE_PRESENT: u32 = 1;
pub const SAMPLE_DIELECTRIC: u32 = 2;

/// One G-buffer pixel ([`slc_core::GSample`] or an empty pixel) as the shading pass reads it.
/// Keep in sync with `Sample` in `shaders/gsample.wgsl` (64 bytes: a 1920 x 1080 G-buffer fits
/// lavapipe's 128 MiB storage binding).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuSample {
    /// Unit shading normal (xyz) and GGX roughness α (w; along the bitangent where
    /// anisotropic).
    pub normal_alpha: [f32; 4],
    /// Unit direction towards the camera ωo (xyz) and an anisotropy's tangent as its angle
    /// around the normal (w; `slc_bounds::Anisotropy::angle`).
    pub omega_o_phi: [f32; 4],
    /// Diffuse reflectance kd (xyz) and an anisotropy's α_t (w; 0 where isotropic).
    pub kd_alpha_t: [f32; 4],
    /// Schlick F0 (xyz), or the relative index η of a dielectric Fresnel (x).
    pub f0_eta: [f32; 3],
    /// [`SAMPLE_PRESENT`] | [`SAMPLE_DIELECTRIC`]; [`SAMPLE_EMPTY`] for an empty pixel.
    pub flags: u32,
}
const _: () = assert!(std::mem::size_of::<GpuSample>() == 64);

impl GpuSample {
    /// An empty pixel: shaded black.
    pub const EMPTY: Self = Self {
        normal_alpha: [0.0; 4],
        omega_o_phi: [0.0; 4],
        kd_alpha_t: [0.0; 4],
        f0_eta: [0.0; 3],
        flags: SAMPLE_EMPTY,
    };

    /// Packs a G-buffer sample (its position goes to the separate positions array,
    /// [`gpu_position`]); `None` (nothing seen) gives [`Self::EMPTY`].
    pub fn new(sample: Option<&GSample>) -> Self {
        let Some(g) = sample else {
            return Self::EMPTY;
        };
        let (flags, f0_eta) = match g.brdf.fresnel {
            Fresnel::Schlick(f0) => (SAMPLE_PRESENT, f0),
            Fresnel::Dielectric(eta) => (SAMPLE_PRESENT | SAMPLE_DIELECTRIC, Vec3::X * eta),
        };
        let (phi, alpha_t) = g
            .brdf
            .anisotropy
            .map_or((0.0, 0.0), |a| (a.angle(g.normal), a.alpha_t));
        Self {
            normal_alpha: vec4(g.normal, g.brdf.alpha),
            omega_o_phi: vec4(g.omega_o, phi),
            kd_alpha_t: vec4(g.brdf.kd, alpha_t),
            f0_eta: f0_eta.to_array(),
            flags,
        }
    }

    /// Whether the pixel has a sample.
    pub fn is_present(&self) -> bool {
        self.flags & SAMPLE_PRESENT != 0
    }

    /// The sample's BRDF (the inverse of [`Self::new`]'s packing, the tangent rebuilt from
    /// its angle).
    pub fn brdf(&self) -> Brdf {
        let normal = Vec3::new(
            self.normal_alpha[0],
            self.normal_alpha[1],
            self.normal_alpha[2],
        );
        Brdf {
            kd: Vec3::new(self.kd_alpha_t[0], self.kd_alpha_t[1], self.kd_alpha_t[2]),
            fresnel: match self.flags & SAMPLE_DIELECTRIC != 0 {
                true => Fresnel::Dielectric(self.f0_eta[0]),
                false => Fresnel::Schlick(Vec3::from_array(self.f0_eta)),
            },
            alpha: self.normal_alpha[3],
            anisotropy: (self.kd_alpha_t[3] > 0.0)
                .then(|| Anisotropy::from_angle(normal, self.omega_o_phi[3], self.kd_alpha_t[3])),
        }
    }
}

/// A G-buffer sample's entry in the positions array every pass reads beside the
/// [`GpuSample`]s: `[x, y, z, 1]`, zero where the pixel has no sample.
pub fn gpu_position(sample: Option<&GSample>) -> [f32; 4] {
    sample.map_or([0.0; 4], |s| s.position.extend(1.0).to_array())
}

/// Parameters of the shading pass. Keep in sync with `ShadeParams` in `shaders/vpl_eval.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuShadeParams {
    pub width: u32,
    pub height: u32,
    pub pixel_count: u32,
    pub vpl_count: u32,
    /// Number of light lists (list ids at or beyond it shade nothing).
    pub list_count: u32,
    /// δ of eq. (2).
    pub delta: f32,
    /// K² of the interleaved sampling (section 6, [`slc_core::Interleaving::scale`]).
    pub scale: f32,
    pub pad: u32,
}
const _: () = assert!(std::mem::size_of::<GpuShadeParams>() == 32);

/// The size naga gives the WGSL struct `name` of `source`: what the layout tests of every
/// `*_types.rs` compare their Rust twins with.
#[cfg(test)]
pub(crate) fn wgsl_size(source: &str, name: &str) -> usize {
    use wgpu::naga;
    let module = naga::front::wgsl::parse_str(source).unwrap();
    let span = module.types.iter().find_map(|(_, ty)| match &ty.inner {
        naga::TypeInner::Struct { span, .. } if ty.name.as_deref() == Some(name) => Some(*span),
        _ => None,
    });
    span.unwrap_or_else(|| panic!("no struct {name}")) as usize
}

#[cfg(test)]
mod tests {
    use super::wgsl_size;
    use super::*;

    /// Every Rust struct has the size of its WGSL twin as the shader compiler lays it out.
    #[test]
    fn sizes_match_the_wgsl_twins() {
        use std::mem::size_of;
        let cases = [
            (crate::rng_pass::SOURCE, "RngParams", size_of::<RngParams>()),
            (crate::rng_pass::SOURCE, "RngSample", size_of::<RngSample>()),
            (crate::bounds_pass::SOURCE, "Vpl", size_of::<GpuVpl>()),
            (crate::bounds_pass::SOURCE, "View", size_of::<GpuView>()),
            (crate::bounds_pass::SOURCE, "Bound", size_of::<GpuBound>()),
            (
                crate::tile_depth_pass::SOURCE,
                "CullParams",
                size_of::<GpuCullParams>(),
            ),
            (
                crate::tile_depth_pass::SOURCE,
                "TileFrusta",
                size_of::<GpuTileFrusta>(),
            ),
            (
                crate::tiled_cull_pass::SOURCE,
                "CullParams",
                size_of::<GpuCullParams>(),
            ),
            (
                crate::tiled_cull_pass::SOURCE,
                "Bound",
                size_of::<GpuBound>(),
            ),
            (
                crate::scan_pass::SOURCE,
                "ScanParams",
                size_of::<GpuScanParams>(),
            ),
            (
                crate::partition_pass::SOURCE,
                "PartitionParams",
                size_of::<GpuPartitionParams>(),
            ),
            (
                crate::shade_pass::SOURCE,
                "ShadeParams",
                size_of::<GpuShadeParams>(),
            ),
            (crate::shade_pass::SOURCE, "Sample", size_of::<GpuSample>()),
            (crate::shade_pass::SOURCE, "Vpl", size_of::<GpuVpl>()),
        ];
        for (source, name, size) in cases {
            assert_eq!(wgsl_size(source, name), size, "{name}");
        }
    }
}
