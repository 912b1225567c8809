//! One whole frame on any backend: prepare, shade with the settings' method, average over
//! `spp` passes.
use crate::frame::{merge_optional, Method, RenderError, RenderSettings, RenderedFrame, Timings};
use crate::framebuffer::Image;
use crate::progress::Progress;
use crate::renderer::{PreparedFrame, Renderer};
use crate::rng::pcg_hash;
use crate::scene::Scene;
use crate::shader::{AllVplShader, SampledLights, SampledShader, ShadeInput, Shader};
use glam::Vec3;
use std::collections::BTreeMap;

/// The seed of ξ, interleaving and sampled points of pass `pass` (`None`: the one pass of a
/// frame without jitter).
pub fn pass_seed(seed: u32, pass: Option<u32>) -> u32 {
    pass.map_or(seed, |p| seed ^ pcg_hash(p))
}

/// Indirect light of a prepared frame by `method` (any but the path method, which
/// [`render`] traces without a prepared frame).
pub fn shade_method<R: Renderer>(
    r: &R,
    method: &Method,
    input: ShadeInput<'_, R>,
    progress: Progress,
) -> Result<crate::frame::Shaded, RenderError> {
    match method {
        Method::Stochastic(s) => s.shade(r, input, progress),
        Method::Vsgl(sampling) => SampledShader {
            lights: SampledLights::Vsgl,
            sampling: *sampling,
        }
        .shade(r, input, progress),
        Method::SampledVpls(sampling) => SampledShader {
            lights: SampledLights::Vpl,
            sampling: *sampling,
        }
        .shade(r, input, progress),
        Method::VplReference => AllVplShader.shade(r, input, progress),
        Method::Path => Err(RenderError::Settings(
            "the path method traces paths, it does not shade a prepared frame".into(),
        )),
    }
}

/// The settings, the backend's support of them and the scene, checked before any work (a
/// cheap check, repeated by [`render_loaded`] for its own callers).
fn check<R: Renderer>(r: &R, scene: &Scene, settings: &RenderSettings) -> Result<(), RenderError> {
    settings.validate()?;
    r.check(settings)?;
    Ok(scene.validate_for_render()?)
}

/// Renders `scene` with `settings` on `r`. `progress` is told the number of pixel-passes
/// finished where the backend counts them (the total is `width * height * spp`) and checked
/// between passes and tiles: once it is cancelled the frame stops with
/// [`RenderError::Cancelled`].
pub fn render<R: Renderer>(
    r: &R,
    scene: &Scene,
    settings: &RenderSettings,
    progress: Progress,
) -> Result<RenderedFrame, RenderError> {
    check(r, scene, settings)?;
    let mut timings = Timings::default();
    progress.check()?;
    let loaded = timings.time("load", || r.load(scene))?;
    let mut frame = render_loaded(r, scene, &loaded, settings, progress)?;
    timings.merge(&frame.timings);
    frame.timings = timings;
    Ok(frame)
}

/// [`render`] of a scene `r` has loaded already (`loaded` from [`Renderer::load`] of the same
/// `scene`), for a caller that renders it many times: the timings have no `load` pass.
pub fn render_loaded<R: Renderer>(
    r: &R,
    scene: &Scene,
    loaded: &R::Scene,
    settings: &RenderSettings,
    progress: Progress,
) -> Result<RenderedFrame, RenderError> {
    check(r, scene, settings)?;
    let (w, h) = (settings.width, settings.height);
    let mut timings = Timings::default();
    let mut gpu_timings = None;
    let readback_before = r.readback_bytes();
    let mut sums = Sums {
        size: (w, h),
        images: None,
    };
    let (mut vpl_count, mut metrics, mut sampled_lights) = (0, None, None);
    for pass in 0..settings.spp {
        progress.check()?;
        if settings.method == Method::Path {
            let (d, i) = timings.time("path", || {
                r.path_trace(scene, loaded, settings, pass, progress)
            })?;
            progress.check()?;
            d.check_finite("direct")?;
            i.check_finite("path")?;
            sums.add([d, i]);
            continue;
        }
        let jitter = (settings.spp > 1).then_some(pass);
        let p = r.prepare(scene, loaded, settings, jitter, progress)?;
        progress.check()?;
        timings.merge(p.timings());
        merge_optional(&mut gpu_timings, p.gpu_timings());
        let input = ShadeInput {
            scene,
            loaded,
            prepared: &p,
            seed: pass_seed(settings.seed, jitter),
            visibility: settings.visibility,
        };
        let shaded = shade_method(r, &settings.method, input, progress)?;
        progress.check()?;
        timings.merge(&shaded.timings);
        merge_optional(&mut gpu_timings, shaded.gpu_timings.as_ref());
        p.direct().check_finite("direct")?;
        shaded.indirect.check_finite("indirect")?;
        vpl_count = p.vpl_count()?;
        metrics = shaded.metrics;
        sampled_lights = shaded.sampled_lights;
        sums.add([p.direct().clone(), shaded.indirect]);
    }
    let [direct, indirect] = sums.mean(settings.spp);
    Ok(RenderedFrame {
        direct,
        indirect,
        vpl_count,
        timings,
        gpu_timings,
        metrics,
        sampled_lights,
        readback_bytes: readback_since(r, readback_before),
    })
}

/// The direct and indirect images of a frame's passes summed pixel by pixel, in the passes'
/// order, as a sum that starts from black images would be (bit for bit: the first pass's
/// pixels plus zero, the others added in place), without those black images or a new image
/// per pass: at 1920x1080 a new image and a copy per pass took 11 ms of zeros and 17 of
/// sums per frame (docs/cpu-frame.md).
struct Sums {
    /// The frame's width and height, which every image must have.
    size: (u32, u32),
    images: Option<[Image; 2]>,
}

impl Sums {
    fn add(&mut self, images: [Image; 2]) {
        match &mut self.images {
            None => {
                self.images = Some(images.map(|mut image| {
                    assert_eq!((image.width, image.height), self.size);
                    // 0 + x is x but for x = −0, which becomes +0.
                    for px in &mut image.pixels {
                        *px += Vec3::ZERO;
                    }
                    image
                }))
            }
            Some(sums) => {
                for (sum, image) in sums.iter_mut().zip(&images) {
                    sum.add_assign(image);
                }
            }
        }
    }

    /// The mean of `passes` passes' sums (black images where none was added); with one pass
    /// the sum itself (x·1 = x for every finite x).
    fn mean(self, passes: u32) -> [Image; 2] {
        let (w, h) = self.size;
        let mut images = (self.images).unwrap_or_else(|| [Image::new(w, h), Image::new(w, h)]);
        if passes > 1 {
            let inv = 1.0 / passes as f32;
            for px in images.iter_mut().flat_map(|image| image.pixels.iter_mut()) {
                *px *= inv;
            }
        }
        images
    }
}

/// The bytes `r` read back since its counters were `before` ([`Renderer::readback_bytes`]),
/// by what was read.
pub fn readback_since<R: Renderer>(
    r: &R,
    before: Option<BTreeMap<String, u64>>,
) -> Option<BTreeMap<String, u64>> {
    let (now, before) = (r.readback_bytes()?, before.unwrap_or_default());
    Some(
        now.into_iter()
            .map(|(k, v)| {
                let d = v - before.get(&k).copied().unwrap_or(0);
                (k, d)
            })
            .filter(|(_, d)| *d > 0)
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sums are those of black images plus every pass with [`Image::add`], bit for bit:
    /// a −0 of the first pass becomes +0, later passes' are added as they are.
    #[test]
    fn sums_equal_a_sum_from_black_images() {
        let (w, h) = (3, 2);
        let pass = |k: f32| {
            let mut image = Image::new(w, h);
            for (i, px) in image.pixels.iter_mut().enumerate() {
                *px = Vec3::new(k * i as f32 + 0.1, -0.0, 1e-30 * k);
            }
            image.pixels[2] = Vec3::new(-0.0, 3.0e38, -1e-38);
            image
        };
        for passes in 1..=3 {
            let mut sums = Sums {
                size: (w, h),
                images: None,
            };
            let (mut direct, mut indirect) = (Image::new(w, h), Image::new(w, h));
            for k in 0..passes {
                let (d, i) = (pass(k as f32 + 1.0), pass(-(k as f32) - 0.5));
                direct = direct.add(&d);
                indirect = indirect.add(&i);
                sums.add([d, i]);
            }
            let bits = |image: &Image| -> Vec<[u32; 3]> {
                image
                    .pixels
                    .iter()
                    .map(|p| p.to_array().map(f32::to_bits))
                    .collect()
            };
            let [d, i] = sums.images.unwrap();
            assert_eq!(bits(&d), bits(&direct), "{passes} passes");
            assert_eq!(bits(&i), bits(&indirect), "{passes} passes");
        }
    }
}
