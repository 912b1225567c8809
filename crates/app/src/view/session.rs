//! What the view shows and how it got there: the scene with its moved lights, the fly
//! camera, the controls and the last rendered frame; it renders again when any of them
//! changed, and saves screenshots' names and settings files.
use super::camera::FlyCamera;
use super::controls::Controls;
use super::frame::{FrameRenderer, ViewFrame};
use super::scene_toml::{settings_toml, SceneOrigin};
use super::{ViewArgs, ViewError};
use slc_core::{Camera, Light, RenderSettings, Scene, Timings};
use std::path::{Path, PathBuf};

/// The view's state, independent of the window.
pub struct Session {
    pub scene: Scene,
    /// Where the scene came from, for saved settings (an error for built-in scenes).
    origin: Result<SceneOrigin, String>,
    pub controls: Controls,
    pub fly: FlyCamera,
    pub selected_light: usize,
    pub width: u32,
    pub height: u32,
    out: PathBuf,
    saved: u32,
    /// The last frame rendered, and what it was rendered with.
    pub frame: Option<ViewFrame>,
    rendered: Option<(RenderSettings, Camera, Vec<Light>)>,
    /// Counts rendered frames (the picture is made again when it changes).
    pub generation: u64,
    /// Per-pass times of every frame rendered with `--frames`, its whole wall-clock time and
    /// the view's own milliseconds.
    pub history: Vec<(Timings, f64, f64)>,
    /// The last message for the panel: a saved file or an error.
    pub status: String,
}

impl Session {
    /// A session on `scene`, opened from `spec`, with the command line's controls.
    pub fn new(args: &ViewArgs, spec: &str, scene: Scene, controls: Controls) -> Self {
        Self {
            origin: SceneOrigin::of(spec, &scene),
            fly: FlyCamera::new(&scene),
            scene,
            controls,
            selected_light: 0,
            width: args.width,
            height: args.height,
            out: args.out.clone(),
            saved: 0,
            frame: None,
            rendered: None,
            generation: 0,
            history: Vec::new(),
            status: String::new(),
        }
    }

    /// Renders a new frame if the camera, a light or a render control changed since the
    /// last one, or always with `force`; returns whether it did.
    pub fn update(&mut self, r: &FrameRenderer, force: bool) -> Result<bool, ViewError> {
        let settings = self
            .controls
            .settings(self.width, self.height)
            .map_err(ViewError::Input)?;
        let camera = self.fly.camera().clone();
        let key = (settings, camera, self.scene.lights.clone());
        if !force && self.rendered.as_ref() == Some(&key) {
            return Ok(false);
        }
        self.scene.camera = Some(key.1.clone());
        let frame = r.render(&self.scene, &key.0).map_err(ViewError::Render)?;
        self.frame = Some(frame);
        self.rendered = Some(key);
        self.generation += 1;
        Ok(true)
    }

    /// The next free path `slc-view-NNN.EXT` in the output folder.
    pub fn next_path(&mut self, ext: &str) -> PathBuf {
        loop {
            self.saved += 1;
            let p = self.out.join(format!("slc-view-{:03}.{ext}", self.saved));
            if !p.exists() {
                return p;
            }
        }
    }

    /// Writes the current camera, lights and scene as a settings file at `path`.
    pub fn save_settings(&self, path: &Path) -> Result<(), ViewError> {
        let origin = self
            .origin
            .as_ref()
            .map_err(|m| ViewError::Input(m.clone()))?;
        let text = settings_toml(
            origin,
            self.fly.camera(),
            &self.scene.lights,
            &format!(
                "slc render {} {}",
                path.display(),
                self.controls.render_options(self.width, self.height)
            ),
        )
        .map_err(ViewError::Input)?;
        std::fs::write(path, text).map_err(|e| ViewError::Write {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
    }

    /// The median milliseconds of each pass over the frames after the first (all frames if
    /// there is only one), then their sum, the whole frame's wall-clock time and the view's own.
    pub fn median_timings(&self) -> Vec<(&'static str, f64)> {
        let frames = &self.history[usize::from(self.history.len() > 1)..];
        let Some((first, ..)) = frames.first() else {
            return Vec::new();
        };
        let median = |mut v: Vec<f64>| {
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let column =
            |f: &dyn Fn(&(Timings, f64, f64)) -> f64| median(frames.iter().map(f).collect());
        let mut rows: Vec<_> = first
            .0
            .iter()
            .map(|&(name, _)| (name, column(&|h| h.0.get(name))))
            .collect();
        rows.push(("frame", column(&|h| h.0.total())));
        rows.push(("whole_frame", column(&|h| h.1)));
        rows.push(("display", column(&|h| h.2)));
        rows
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        view: ViewArgs,
    }

    /// A device, or `None` (a notice; a failure with `CI` set) without an adapter.
    fn gpu() -> Option<slc_gpu_wgpu::GpuContext> {
        match slc_gpu_wgpu::GpuContext::new() {
            Ok(g) => Some(g),
            Err(e) if std::env::var_os("CI").is_none() => {
                eprintln!("notice: GPU test skipped ({e})");
                None
            }
            Err(e) => panic!("CI is set but the GPU renderer is missing: {e}"),
        }
    }

    #[test]
    fn a_moved_light_or_camera_renders_again_and_nothing_else_does() {
        for backend in ["gpu", "cpu"] {
            moved_light_or_camera_renders_again(backend);
        }
    }

    fn moved_light_or_camera_renders_again(backend: &str) {
        let Some(ctx) = gpu() else {
            return;
        };
        let args = Cli::parse_from([
            "slc",
            "--width",
            "48",
            "--height",
            "32",
            "--rsm",
            "8",
            "--backend",
            backend,
        ])
        .view;
        let scene = slc_core::builtin("default").unwrap();
        let mut s = Session::new(&args, "default", scene, Controls::from_args(&args));
        let r = FrameRenderer::new(args.backend, ctx, &s.scene).unwrap();
        assert!(s.update(&r, false).unwrap());
        assert!(!s.update(&r, false).unwrap(), "nothing changed");
        let before = s
            .frame
            .as_ref()
            .map(|f| (f.direct.clone(), f.indirect.clone()))
            .unwrap();
        for light in &mut s.scene.lights {
            if let Light::Spot { position, .. } | Light::Point { position, .. } = light {
                position.x -= 0.4;
            }
        }
        assert!(s.update(&r, false).unwrap());
        let f = s.frame.as_ref().unwrap();
        assert!(f.direct.rmse(&before.0) > 1e-3, "direct light did not move");
        assert!(
            f.indirect.rmse(&before.1) > 1e-4,
            "indirect light did not move"
        );
        s.fly.apply(
            &super::super::camera::FlyInput {
                forward: 1.0,
                ..Default::default()
            },
            0.5,
        );
        assert!(s.update(&r, false).unwrap());
        assert_eq!(s.generation, 3);
    }
}
