//! Reflective shadow maps traced from the light: the surface points the light's photons reach
//! first, with the flux each texel carries, on the faces of [`RsmLayout`] (`slc_core::rsm`,
//! which the GPU's rasterized maps share).
use crate::blocks::par_blocks;
use crate::tracer::{Rays8, SurfaceHit, Tracer};
use glam::Vec3;
use slc_core::rng::{stream, Sequence};
use slc_core::rsm::RsmFace;
pub use slc_core::rsm::{rectangle_solid_angle, Rsm, RsmLayout, RsmTexel};
use slc_core::{Emitter, Light, Scene};

/// Where inside each texel the light's ray goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TexelSample {
    /// Through the texel centre, with the texel's exact solid angle (as a rasterizer would).
    Centre,
    /// At a uniformly random point of the texel (pass `pass` of `seed`), with the flux divided
    /// by that point's density: an unbiased estimate of the light's one-bounce transport.
    Jittered { seed: u32, pass: u32 },
}

/// Traces the reflective shadow map of `light`: its texels' rays from the light in 4x2
/// blocks of the faces stacked one above the other, each block's rays traced together
/// ([`Tracer::intersect_rays8`]; the same hits as ray by ray).
pub fn trace_rsm(
    scene: &Scene,
    tracer: &Tracer,
    light: &Light,
    resolution: u32,
    sample: TexelSample,
) -> Rsm {
    let n = resolution;
    let rays = TexelRays::new(scene, light, n, sample);
    // The faces one above the other: texel (i, j) of face f is pixel (i, f n + j), whose
    // row-major index is the texel's index.
    let texels = par_blocks(n, rays.faces.len() as u32 * n, Vec::new(), |block| {
        let mut packet = Rays8::default();
        let mut texel_rays = [None; 8];
        for lane in block.lanes() {
            if let Some(ray) = rays.ray(block.index(lane) as u32) {
                packet.origin[lane] = ray.origin;
                packet.dir[lane] = ray.dir;
                packet.used |= 1 << lane;
                texel_rays[lane] = Some(ray);
            }
        }
        let hits = tracer.intersect_rays8(scene, &packet);
        std::array::from_fn(|lane| rays.texel(&texel_rays[lane]?, hits[lane]?))
    });
    Rsm {
        resolution: n,
        faces: rays.faces.len() as u32,
        texels,
    }
}

/// A texel's ray, the flux it carries and its beam: the beam's cross-section (orthographic)
/// or solid angle (perspective: the cross-section is `beam` times the squared distance).
#[derive(Clone, Copy, Debug)]
struct TexelRay {
    origin: Vec3,
    dir: Vec3,
    flux: Vec3,
    beam: f32,
}

/// What a texel's ray and its texel are formed from: the light, its map's faces and origin
/// ([`RsmLayout`]), the resolution n and a texel's size on a face (2/n), and where in a texel
/// its ray goes.
struct TexelRays<'a> {
    emitter: Emitter<'a>,
    faces: Vec<RsmFace>,
    origin: Vec3,
    orthographic: bool,
    n: u32,
    texel_size: f32,
    sample: TexelSample,
}

impl<'a> TexelRays<'a> {
    fn new(scene: &Scene, light: &'a Light, n: u32, sample: TexelSample) -> Self {
        let bounds = scene.bounds().unwrap_or((Vec3::splat(-1.0), Vec3::ONE));
        let RsmLayout {
            faces,
            origin,
            orthographic,
        } = RsmLayout::new(light, bounds);
        Self {
            emitter: light.emitter(),
            faces,
            origin,
            orthographic: orthographic.is_some(),
            n,
            texel_size: 2.0 / n as f32,
            sample,
        }
    }

    /// Texel `index`'s ray; `None` where it carries no flux.
    fn ray(&self, index: u32) -> Option<TexelRay> {
        let (n, texel_size, light) = (self.n, self.texel_size, self.emitter.light());
        let face = self.faces[(index / (n * n)) as usize];
        let (i, j) = (index % n, (index / n) % n);
        let (s, t) = match self.sample {
            TexelSample::Centre => (0.5, 0.5),
            TexelSample::Jittered { seed, pass } => {
                Sequence::new(seed, index, stream::RSM_JITTER, 2 * pass).next_2d()
            }
        };
        let e = face.extent;
        let x = (-1.0 + (i as f32 + s) * texel_size) * e;
        let y = (1.0 - (j as f32 + t) * texel_size) * e;
        let (origin, dir, flux, beam) = if self.orthographic {
            let area = (texel_size * e) * (texel_size * e);
            let irradiance = match *light {
                Light::Directional { irradiance, .. } => irradiance,
                _ => unreachable!("only directional lights are orthographic"),
            };
            (
                self.origin + x * face.right + y * face.up,
                face.forward,
                irradiance * area,
                area,
            )
        } else {
            let dir = (face.forward + x * face.right + y * face.up).normalize();
            let solid_angle = match self.sample {
                TexelSample::Centre => {
                    let (x0, y1) = (
                        (-1.0 + i as f32 * texel_size) * e,
                        (1.0 - j as f32 * texel_size) * e,
                    );
                    rectangle_solid_angle(x0, x0 + texel_size * e, y1 - texel_size * e, y1)
                }
                // Density of a uniform point on the texel, in solid angle:
                // dω = dA / (1 + x² + y²)^{3/2} on the plane at unit distance.
                TexelSample::Jittered { .. } => {
                    (texel_size * e).powi(2) / (1.0 + x * x + y * y).powf(1.5)
                }
            };
            let intensity = match *light {
                Light::Point { intensity, .. } => intensity,
                Light::Spot { intensity, .. } => intensity * self.emitter.spot_falloff(dir),
                Light::Directional { .. } => {
                    unreachable!("directional lights are orthographic")
                }
            };
            (self.origin, dir, intensity * solid_angle, solid_angle)
        };
        if flux.max_element() <= 0.0 {
            None
        } else {
            Some(TexelRay {
                origin,
                dir,
                flux,
                beam,
            })
        }
    }

    /// The texel of `ray`, which meets `hit`; `None` on the back of a one-sided surface.
    fn texel(&self, ray: &TexelRay, hit: SurfaceHit) -> Option<RsmTexel> {
        let cross_section = if self.orthographic {
            ray.beam
        } else {
            ray.beam * hit.distance * hit.distance
        };
        hit.front.then_some(RsmTexel {
            position: hit.position,
            normal: hit.shading_normal,
            geometric_normal: hit.geometric_normal,
            normal_mapped: hit.normal_mapped,
            omega_i: -ray.dir,
            flux: ray.flux,
            cross_section,
            brdf: hit.brdf,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use slc_core::builtin;

    /// The texels traced in packets are those of each texel's ray traced alone, bit for bit:
    /// the built-in scene's spot light, a point light inside the room (six faces) and a
    /// directional light through the room's open side (orthographic, origins differing per
    /// texel), at an odd resolution (blocks across two faces) and an even one, through texel
    /// centres and jittered; each light gives texels (so a wrong hit cannot pass as two
    /// misses).
    #[test]
    fn packets_give_each_texel_its_own_hit() {
        let scene = builtin("default").unwrap();
        let tracer = Tracer::new(&scene);
        let lights = [
            scene.lights[0].clone(),
            Light::Point {
                position: Vec3::new(0.1, 1.5, 0.2),
                intensity: Vec3::splat(3.0),
            },
            // Into the room through its open side (z = 1).
            Light::Directional {
                direction: Vec3::new(0.2, -0.6, -1.0).normalize(),
                irradiance: Vec3::splat(2.0),
            },
        ];
        for light in &lights {
            for n in [37, 32] {
                for sample in [
                    TexelSample::Centre,
                    TexelSample::Jittered { seed: 5, pass: 1 },
                ] {
                    let rsm = trace_rsm(&scene, &tracer, light, n, sample);
                    let rays = TexelRays::new(&scene, light, n, sample);
                    assert_eq!(rsm.texels.len(), rays.faces.len() * (n * n) as usize);
                    let (mut met, mut lit) = (0, 0);
                    for (index, got) in rsm.texels.iter().enumerate() {
                        let alone = rays.ray(index as u32).and_then(|ray| {
                            let hit =
                                tracer.intersect(&scene, ray.origin, ray.dir, f32::INFINITY)?;
                            met += 1;
                            rays.texel(&ray, hit)
                        });
                        // Compared as printed: every float to its shortest exact form.
                        assert_eq!(
                            format!("{got:?}"),
                            format!("{alone:?}"),
                            "{light:?} n {n} texel {index}"
                        );
                        lit += usize::from(got.is_some());
                    }
                    assert!(met > rsm.texels.len() / 10, "{met} of {}", rsm.texels.len());
                    assert!(lit > met / 4, "{light:?}: {lit} texels of {met} hits");
                }
            }
        }
    }
}
