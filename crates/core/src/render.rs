//! One whole frame on any backend: prepare, shade with the settings' method, average over
//! `spp` passes.
use crate::frame::{merge_optional, Method, RenderError, RenderSettings, RenderedFrame, Timings};
use crate::framebuffer::Image;
use crate::progress::Progress;
use crate::renderer::{PreparedFrame, Renderer};
use crate::rng::pcg_hash;
use crate::scene::Scene;
use crate::shader::{AllVplShader, SampledLights, SampledShader, ShadeInput, Shader};
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
    let mut frame = RenderedFrame {
        direct: Image::new(w, h),
        indirect: Image::new(w, h),
        vpl_count: 0,
        timings: Timings::default(),
        gpu_timings: None,
        metrics: None,
        sampled_lights: None,
        readback_bytes: None,
    };
    for pass in 0..settings.spp {
        progress.check()?;
        if settings.method == Method::Path {
            let (d, i) = timings.time("path", || {
                r.path_trace(scene, loaded, settings, pass, progress)
            })?;
            progress.check()?;
            d.check_finite("direct")?;
            i.check_finite("path")?;
            frame.direct = frame.direct.add(&d);
            frame.indirect = frame.indirect.add(&i);
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
        frame.vpl_count = p.vpl_count()?;
        frame.metrics = shaded.metrics;
        frame.sampled_lights = shaded.sampled_lights;
        frame.direct = frame.direct.add(p.direct());
        frame.indirect = frame.indirect.add(&shaded.indirect);
    }
    let inv = 1.0 / settings.spp as f32;
    for px in frame
        .direct
        .pixels
        .iter_mut()
        .chain(frame.indirect.pixels.iter_mut())
    {
        *px *= inv;
    }
    frame.timings = timings;
    frame.gpu_timings = gpu_timings;
    frame.readback_bytes = readback_since(r, readback_before);
    Ok(frame)
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
