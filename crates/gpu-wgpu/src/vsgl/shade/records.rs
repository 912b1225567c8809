//! `#[repr(C)]` twins of the WGSL structs of the VSGL shading pass (`vsgl_shade.wesl`),
//! in the convention of every `records.rs` (a compile-time size check and a unit test
//! against the layout naga computes from the shader), and the validation that turns a VSGL
//! into its GPU form as `slc_cpu_ref::vsgl`'s `Emitter::new` prepares it.
use crate::device::context::GpuError;
use bytemuck::{Pod, Zeroable};
use core::f32::consts::{FRAC_1_PI, TAU};
use glam::Vec3;
use slc_bounds::sg::{mixture_scale, sg_integral, LobeStretch, MIXTURE_FROM};
use slc_bounds::SphericalGaussian;

/// One lobe `c_v G(ω; ξ_v, λ_v)` of a VSGL's radiant intensity (VSGL section 3.1.1): the
/// fields `c_diffuse`, `xi_diffuse`, `lambda_diffuse` (or the specular ones) of
/// `slc_cpu_ref::vsgl::Vsgl`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VsglLobe {
    /// `c_v` per channel (already times the sample's Monte Carlo weight).
    pub c: Vec3,
    /// The lobe axis `ξ_v` (unit within 1e-3).
    pub xi: Vec3,
    /// The sharpness `λ_v` (finite, ≥ 0).
    pub lambda: f32,
}

/// A VSGL as the shading pass takes it: positional mean `μ_v`, variance `σ_v²` (section
/// 3.1.2) and its `[diffuse, specular]` lobes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VsglInput {
    pub mu: Vec3,
    pub sigma2: f32,
    pub lobes: [VsglLobe; 2],
    /// How the diffuse lobe emits (`slc_cpu_ref::vsgl::DiffuseEmission`): `None` as the
    /// paper's SG, `Some(κ)` as the clamped cosine convolved with a von Mises-Fisher normal
    /// distribution of concentration κ (`Vsgl::normal_concentration`) about `ξ_v`, of peak
    /// `c_v A(λ_v)/π`.
    pub clamped_diffuse: Option<f32>,
    /// The direction of the cluster's specular-weighted mean normal
    /// (`slc_cpu_ref::vsgl::Vsgl::specular_normal`; zero: unknown), for the specular lobe's
    /// stretch ([`LobeStretch`]).
    pub specular_normal: Vec3,
}

/// Parameters of the VSGL shading pass. Keep in sync with `VsglParams` in
/// `vsgl_shade.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuVsglParams {
    pub pixel_count: u32,
    pub vsgl_count: u32,
    pub pad: [u32; 2],
}
const _: () = assert!(std::mem::size_of::<GpuVsglParams>() == 16);

/// A VSGL prepared for shading, the twin of `Emitter` in `crates/cpu-ref/src/vsgl/shading.rs`.
/// Keep in sync with `Vsgl` in `vsgl_shade.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuVsgl {
    /// `μ_v` (xyz) and `σ_v²` (w).
    pub mu_sigma2: [f32; 4],
    /// `c_v` of the diffuse lobe (xyz; zero: left out) and `1/(2πσ_v²)` of eq. (1) and (5) (w).
    pub diffuse_c_density: [f32; 4],
    /// The emitted diffuse lobe's axis `−ξ_v` (xyz) and `λ_v` (w).
    pub diffuse_lobe: [f32; 4],
    /// `c_v` of the specular lobe (xyz; zero: left out), times the scale `s(λ_v)` of its
    /// three SGs where it is shaded as GGX's mixture (`slc_bounds::sg::mixture_scale`, from
    /// `MIXTURE_FROM` on: once here rather than per pixel); w: 1 when the diffuse lobe is the
    /// clamped cosine (then `diffuse_c_density.xyz` is its peak `c_v A(λ_v)/π` and
    /// `diffuse_lobe` holds `ξ_v` and κ), 0 for the SG.
    pub specular_c: [f32; 4],
    /// The emitted specular lobe's axis `−ξ_v` (xyz) and `λ_v` (w).
    pub specular_lobe: [f32; 4],
    /// The specular lobe's [`LobeStretch`]: the tangent in the plane of incidence (xyz) and
    /// `cos θ` (w).
    pub stretch_tangent: [f32; 4],
    /// The bitangent across the plane (xyz) and `1 / cos θ` (w).
    pub stretch_bitangent: [f32; 4],
}
const _: () = assert!(std::mem::size_of::<GpuVsgl>() == 112);

impl GpuVsgl {
    /// Packs VSGL `index` after the CPU's checks (`Emitter::new`): `σ_v²` positive with a
    /// finite `1/(2πσ_v²)`, each used lobe (non-zero `c_v`) a valid SG `G(ω; −ξ_v, λ_v)`
    /// (axis renormalised as the CPU does); beyond the CPU, `μ_v` and `c_v` must be finite and
    /// `c_v` non-negative, so that no NaN reaches the image.
    pub fn new(vsgl: &VsglInput, index: usize) -> Result<Self, GpuError> {
        let bad = |what: String| GpuError::Input(format!("VSGL {index}: {what}"));
        let sigma2 = vsgl.sigma2;
        let density = 1.0 / (TAU * sigma2);
        if !(sigma2 > 0.0 && density.is_finite()) {
            return Err(bad(format!(
                "the positional variance must be positive and finite, got {sigma2}"
            )));
        }
        if !vsgl.mu.is_finite() {
            return Err(bad(format!("μ_v {} is not finite", vsgl.mu)));
        }
        let mut packed = [([0.0f32; 4], [0.0f32; 4]); 2];
        for (k, (lobe, out)) in vsgl.lobes.iter().zip(&mut packed).enumerate() {
            if !(lobe.c.is_finite() && lobe.c.min_element() >= 0.0) {
                return Err(bad(format!("c_v {} is not finite and >= 0", lobe.c)));
            }
            if lobe.c == Vec3::ZERO {
                continue;
            }
            *out = match vsgl.clamped_diffuse {
                Some(kappa) if k == 0 => {
                    // Emitter::new's ClampedDiffuse: the peak c_v A(λ_v)/π, the normal ξ_v.
                    if !(lobe.xi.is_finite() && lobe.lambda.is_finite() && lobe.lambda >= 0.0)
                        || kappa.is_nan()
                    {
                        return Err(bad(format!(
                            "diffuse axis {} or λ {} or concentration {kappa} invalid",
                            lobe.xi, lobe.lambda
                        )));
                    }
                    let peak = lobe.c * (sg_integral(lobe.lambda) * FRAC_1_PI);
                    if !peak.is_finite() {
                        return Err(bad(format!("diffuse peak {peak} is not finite")));
                    }
                    (
                        [peak.x, peak.y, peak.z, 0.0],
                        [lobe.xi.x, lobe.xi.y, lobe.xi.z, kappa],
                    )
                }
                _ => {
                    let sg = SphericalGaussian::new(-lobe.xi, lobe.lambda, 1.0)
                        .map_err(|e| bad(e.to_string()))?;
                    (
                        [lobe.c.x, lobe.c.y, lobe.c.z, 0.0],
                        [sg.axis.x, sg.axis.y, sg.axis.z, sg.sharpness],
                    )
                }
            };
        }
        let [(cd, ld), (mut cs, ls)] = packed;
        let specular = &vsgl.lobes[1];
        let stretch = if specular.c == Vec3::ZERO {
            LobeStretch::NONE
        } else {
            LobeStretch::new(specular.xi, specular.lambda, vsgl.specular_normal)
        };
        let [t, b] = [stretch.tangent, stretch.bitangent];
        if ls[3] >= MIXTURE_FROM {
            let scaled = Vec3::from_slice(&cs[..3]) * mixture_scale(ls[3]);
            if !scaled.is_finite() {
                return Err(bad(format!("specular c_v {scaled} is not finite")));
            }
            cs[..3].copy_from_slice(&scaled.to_array());
        }
        cs[3] = if vsgl.clamped_diffuse.is_some() {
            1.0
        } else {
            0.0
        };
        Ok(Self {
            mu_sigma2: [vsgl.mu.x, vsgl.mu.y, vsgl.mu.z, sigma2],
            diffuse_c_density: [cd[0], cd[1], cd[2], density],
            diffuse_lobe: ld,
            specular_c: cs,
            specular_lobe: ls,
            stretch_tangent: [t[0], t[1], t[2], stretch.cos],
            stretch_bitangent: [b[0], b[1], b[2], stretch.inv_cos],
        })
    }
}

/// The fault record of a VSGL frame, written by its construction ([`crate::vsgl::build`])
/// and its shading and read once, after the shading. Keep in sync with `VsglStatus` in
/// `vsgl_light.wesl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuVsglStatus {
    /// Smallest pixel whose surface is outside the SG math's domain (`u32::MAX`: none).
    pub bad_pixel: u32,
    /// Smallest VSGL whose `λ_σ` or SG product left `f32` at some pixel (`u32::MAX`: none).
    pub overflow_vsgl: u32,
    /// The distinct clusters the VSGLs stand for (the CPU's number of sampled lights).
    pub lights: u32,
    /// Smallest RSM texel (over the maps in order) whose BRDF is outside the SG math's
    /// domain (`u32::MAX`: none).
    pub bad_texel: u32,
    /// Smallest VSGL whose parameters left `f32` or the shading's domain (`u32::MAX`: none).
    pub bad_vsgl: u32,
    /// Smallest RSM texel whose bidirectional importance left `f32` (`u32::MAX`: none).
    pub bad_view: u32,
    /// [`Self::bad_vsgl`] for the camera-side VSGLs of the bidirectional importance.
    pub bad_camera_vsgl: u32,
    pub pad: u32,
}
const _: () = assert!(std::mem::size_of::<GpuVsglStatus>() == 32);

impl GpuVsglStatus {
    /// The initial record of `lights` VSGLs: no faults.
    pub const fn clear(lights: u32) -> Self {
        Self {
            bad_pixel: u32::MAX,
            overflow_vsgl: u32::MAX,
            lights,
            bad_texel: u32::MAX,
            bad_vsgl: u32::MAX,
            bad_view: u32::MAX,
            bad_camera_vsgl: u32::MAX,
            pad: 0,
        }
    }

    /// The number of lights, or the first fault as an error.
    pub fn lights(&self) -> Result<u32, GpuError> {
        if self.bad_pixel != u32::MAX {
            return Err(GpuError::Input(format!(
                "G-buffer pixel {}: surface outside the SG shading's domain (normal or view \
                 not unit, kd negative or not finite, α outside (0, 1], invalid Fresnel)",
                self.bad_pixel
            )));
        }
        if self.bad_texel != u32::MAX {
            return Err(GpuError::Input(format!(
                "RSM texel {}: surface outside the SG math's domain (normal or light direction \
                 not unit, kd negative or not finite, α outside (0, 1], invalid Fresnel)",
                self.bad_texel
            )));
        }
        if self.bad_view != u32::MAX {
            return Err(GpuError::Input(format!(
                "RSM texel {}: its bidirectional importance leaves f32",
                self.bad_view
            )));
        }
        if self.bad_vsgl != u32::MAX {
            return Err(GpuError::Input(format!(
                "VSGL {}: a coefficient leaves f32 or σ_v² is not positive (raise the σ² floor)",
                self.bad_vsgl
            )));
        }
        if self.bad_camera_vsgl != u32::MAX {
            return Err(GpuError::Input(format!(
                "camera-side VSGL {} of the bidirectional importance: a coefficient leaves f32 \
                 or σ_v² is not positive (raise the σ² floor)",
                self.bad_camera_vsgl
            )));
        }
        if self.overflow_vsgl != u32::MAX {
            return Err(GpuError::Input(format!(
                "VSGL {}: λ_σ = |μ_v − x_p|²/σ_v² or its SG product leaves f32 at some pixel",
                self.overflow_vsgl
            )));
        }
        Ok(self.lights)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::raster::records::GpuSample;

    wgsl_twins! {
        crate::vsgl::shade::SOURCE => {
            GpuVsglParams as "VsglParams",
            GpuVsgl as "Vsgl",
            GpuVsglStatus as "VsglStatus",
            GpuSample as "Sample",
        }
        crate::vsgl::build::SOURCE => {
            GpuVsgl as "Vsgl",
            GpuVsglStatus as "VsglStatus",
        }
    }

    fn input(sigma2: f32) -> VsglInput {
        let lobe = VsglLobe {
            c: Vec3::ONE,
            xi: Vec3::Z,
            lambda: 2.0,
        };
        VsglInput {
            mu: Vec3::ZERO,
            sigma2,
            lobes: [lobe; 2],
            clamped_diffuse: None,
            specular_normal: Vec3::ZERO,
        }
    }

    /// The CPU's refusals (σ² not positive, 1/(2πσ²) infinite, invalid lobes) and the
    /// non-finite values the GPU refuses besides; zero lobes skip the lobe checks.
    #[test]
    fn packing_refuses_out_of_domain_vsgls() {
        let ok = GpuVsgl::new(&input(0.5), 0).unwrap();
        assert_eq!(ok.diffuse_lobe, [0.0, 0.0, -1.0, 2.0]);
        assert_eq!(ok.diffuse_c_density[3], 1.0 / (TAU * 0.5));
        for s in [0.0, -1.0, f32::NAN, 1e-45] {
            assert!(GpuVsgl::new(&input(s), 0).is_err(), "σ² {s}");
        }
        let mut v = input(1.0);
        v.mu.x = f32::INFINITY;
        assert!(GpuVsgl::new(&v, 0).is_err());
        for (c, xi, lambda) in [
            (Vec3::splat(f32::NAN), Vec3::Z, 1.0),
            (-Vec3::X, Vec3::Z, 1.0),
            (Vec3::ONE, Vec3::ZERO, 1.0),
            (Vec3::ONE, Vec3::Z, -1.0),
            (Vec3::ONE, Vec3::Z, f32::INFINITY),
        ] {
            let mut v = input(1.0);
            v.lobes[1] = VsglLobe { c, xi, lambda };
            assert!(GpuVsgl::new(&v, 3).is_err(), "{c} {xi} {lambda}");
        }
        let mut zero = input(1.0);
        zero.lobes[1] = VsglLobe {
            c: Vec3::ZERO,
            xi: Vec3::ZERO,
            lambda: f32::NAN,
        };
        assert_eq!(GpuVsgl::new(&zero, 0).unwrap().specular_lobe, [0.0; 4]);
        // The clamped diffuse emission: its peak c A(λ)/π, the normal ξ (not −ξ) and κ, the
        // flag in specular_c.w; a NaN concentration is refused.
        let clamped = VsglInput {
            clamped_diffuse: Some(40.0),
            ..input(1.0)
        };
        let packed = GpuVsgl::new(&clamped, 0).unwrap();
        let peak = sg_integral(2.0) * FRAC_1_PI;
        assert_eq!(packed.diffuse_c_density[..3], [peak; 3]);
        assert_eq!(packed.diffuse_lobe, [0.0, 0.0, 1.0, 40.0]);
        assert_eq!(packed.specular_c[3], 1.0);
        assert_eq!(ok.specular_c[3], 0.0);
        let nan = VsglInput {
            clamped_diffuse: Some(f32::NAN),
            ..input(1.0)
        };
        assert!(GpuVsgl::new(&nan, 0).is_err());
    }
}
