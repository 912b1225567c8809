//! A rasterized RSM ([`GpuRsm`]) read back as `slc_core`'s [`Rsm`], the form the CPU's
//! passes take (a frame handed to the CPU, and the conformance tests of the GPU's own VSGL
//! construction, `crate::vsgl::build`).
use glam::Vec3;
use slc_bounds::{Brdf, Fresnel};
use slc_core::rsm::{rectangle_solid_angle, Rsm, RsmTexel};

use crate::device::context::{GpuContext, GpuError};
use crate::frame::light::rsm::GpuRsm;
use crate::vpl::records::{anisotropy_from_gpu, FRESNEL_SCHLICK};

fn xyz(v: [f32; 4]) -> Vec3 {
    Vec3::new(v[0], v[1], v[2])
}

/// The RSM texels and shadow map of `rsm`, read back as `trace_rsm(…, TexelSample::Centre)`
/// lays them out. The GPU texel carries position, normal, ωi, flux and BRDF; the two fields
/// it lacks are rebuilt as the CPU forms them: the geometric normal from the shadow map
/// (the same triangle, turned to the lit side; only `|n_g · ωi|` is used, by
/// `footprint_variance`) and the beam's cross-section, the texel's exact solid angle
/// (`rectangle_solid_angle`) times the squared distance from the light, or the texel's area
/// for an orthographic map.
pub fn cpu_rsm(ctx: &GpuContext, rsm: &GpuRsm) -> Result<Rsm, GpuError> {
    let texels = rsm.read_texels(ctx)?;
    let shadow = rsm.read_shadow(ctx)?;
    let n = rsm.resolution;
    let texel_size = 2.0 / n as f32;
    let layout = &rsm.layout;
    let texels = texels
        .iter()
        .zip(&shadow)
        .enumerate()
        .map(|(index, (t, s))| {
            if t.position[3] == 0.0 {
                return None;
            }
            let index = index as u32;
            let face = layout.faces[(index / (n * n)) as usize];
            let (i, j) = (index % n, (index / n) % n);
            let e = face.extent;
            let position = xyz(t.position);
            let cross_section = if layout.orthographic.is_some() {
                (texel_size * e) * (texel_size * e)
            } else {
                let (x0, y1) = (
                    (-1.0 + i as f32 * texel_size) * e,
                    (1.0 - j as f32 * texel_size) * e,
                );
                let solid_angle =
                    rectangle_solid_angle(x0, x0 + texel_size * e, y1 - texel_size * e, y1);
                solid_angle * (position - layout.origin).length_squared()
            };
            let omega_i = xyz(t.omega_i_eta);
            let g = xyz(s.normal);
            let fresnel = if t.fresnel == FRESNEL_SCHLICK {
                Fresnel::Schlick(xyz(t.f0))
            } else {
                Fresnel::Dielectric(t.omega_i_eta[3])
            };
            Some(RsmTexel {
                position,
                normal: xyz(t.normal_alpha),
                geometric_normal: if g.dot(omega_i) < 0.0 { -g } else { g },
                normal_mapped: t.geometric[3] != 0.0,
                omega_i,
                flux: Vec3::from(t.flux),
                cross_section,
                brdf: Brdf {
                    kd: xyz(t.kd),
                    fresnel,
                    alpha: t.normal_alpha[3],
                    anisotropy: anisotropy_from_gpu(t.anisotropy),
                },
            })
        })
        .collect();
    Ok(Rsm {
        resolution: n,
        faces: layout.faces.len() as u32,
        texels,
    })
}
