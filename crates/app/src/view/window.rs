//! The window and its event loop (winit): opening it on the GPU, input to the fly camera,
//! a new frame when anything changed, `--frames` runs that save and exit. The egui contents
//! of a frame are in `ui.rs`, the input in `input.rs`.
use super::camera::FlyInput;
use super::display::Display;
use super::frame::FrameRenderer;
use super::input::{Input, KeyCommand};
use super::screenshot::{capture, save_png, PixelRect};
use super::session::Session;
use super::{ViewArgs, ViewError};
use slc_app::backends::warn_if_software;
use std::collections::VecDeque;
use std::sync::Arc;
use std::time::Instant;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::window::{Window, WindowId};

/// Width of the side panel in pixels.
pub const PANEL_WIDTH: u32 = 330;
/// The least window height: the panel's controls without scrolling (a lower view is centred).
const MIN_HEIGHT: u32 = 760;
/// Seconds one scripted step lasts.
const SCRIPT_DT: f32 = 0.1;
/// The longest frame time the camera integrates (after a slow frame it does not jump).
const MAX_DT: f32 = 0.1;

/// Opens the window and runs the view until it is closed or `--frames` are done.
pub fn run(args: &ViewArgs, session: Session, script: Vec<FlyInput>) -> Result<(), ViewError> {
    let event_loop = EventLoop::new().map_err(|e| {
        if std::env::var_os("DISPLAY").is_none_or(|s| s.is_empty()) {
            ViewError::NoDisplay("DISPLAY is not set".into())
        } else {
            ViewError::Window(e.to_string())
        }
    })?;
    let mut app = App {
        args,
        session,
        script: script.into(),
        frames: 0,
        running: None,
        screenshot_asked: false,
        result: Ok(()),
    };
    event_loop
        .run_app(&mut app)
        .map_err(|e| ViewError::Window(e.to_string()))?;
    app.result
}

struct App<'a> {
    args: &'a ViewArgs,
    session: Session,
    script: VecDeque<FlyInput>,
    /// Frames drawn so far (counted with `--frames`).
    frames: u32,
    running: Option<Running>,
    /// A screenshot was asked for (P or the button): saved once a picture has been drawn.
    screenshot_asked: bool,
    result: Result<(), ViewError>,
}

/// The open window with what draws into it.
pub struct Running {
    pub(super) window: Arc<Window>,
    pub(super) display: Display,
    pub(super) renderer: FrameRenderer,
    pub(super) egui: egui::Context,
    pub(super) egui_state: egui_winit::State,
    pub(super) texture: Option<egui::TextureHandle>,
    /// What the texture shows: the frame's generation and the display controls.
    pub(super) picture_key: Option<(u64, String)>,
    pub(super) note: Option<&'static str>,
    /// Where the picture is in the window (points).
    pub(super) picture_rect: egui::Rect,
    pub(super) input: Input,
    pub(super) last: Instant,
    pub(super) display_ms: f64,
}

impl ApplicationHandler for App<'_> {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() {
            return;
        }
        match self.open(event_loop) {
            Ok(r) => {
                r.window.request_redraw();
                self.running = Some(r);
            }
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(r) = self.running.as_mut() else {
            return;
        };
        let consumed = r.egui_state.on_window_event(&r.window, &event).consumed;
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                r.display
                    .resize(&r.renderer.context().device, size.width, size.height)
            }
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.redraw(event_loop) {
                    self.fail(event_loop, e);
                }
                return;
            }
            other => {
                let over = r.picture_rect_px();
                match r.input.handle(&other, consumed, over) {
                    Some(KeyCommand::Screenshot) => self.screenshot_asked = true,
                    Some(KeyCommand::SaveSettings) => self.save_settings(),
                    None => {}
                }
            }
        }
        if let Some(r) = &self.running {
            r.window.request_redraw();
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(r) = &self.running else {
            return;
        };
        let busy = self.args.frames.is_some() || !r.input.held.is_empty();
        event_loop.set_control_flow(if busy {
            ControlFlow::Poll
        } else {
            ControlFlow::Wait
        });
        if busy {
            r.window.request_redraw();
        }
    }
}

impl App<'_> {
    fn open(&self, event_loop: &ActiveEventLoop) -> Result<Running, ViewError> {
        let s = &self.session;
        let attributes = Window::default_attributes()
            .with_title(format!("slc view: {}", s.scene.name))
            .with_inner_size(PhysicalSize::new(
                s.width + PANEL_WIDTH,
                s.height.max(MIN_HEIGHT),
            ));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| ViewError::Window(e.to_string()))?,
        );
        let (display, ctx) = Display::open(Arc::clone(&window))?;
        let renderer =
            FrameRenderer::new(self.args.backend, ctx, &s.scene).map_err(ViewError::Render)?;
        if renderer.software_gpu() {
            warn_if_software(renderer.context());
        }
        let egui = egui::Context::default();
        let max_side = renderer.context().limits.max_texture_dimension_2d as usize;
        let egui_state = egui_winit::State::new(
            egui.clone(),
            egui::ViewportId::ROOT,
            window.as_ref(),
            Some(window.scale_factor() as f32),
            None,
            Some(max_side),
        );
        Ok(Running {
            window,
            display,
            renderer,
            egui,
            egui_state,
            texture: None,
            picture_key: None,
            note: None,
            picture_rect: egui::Rect::NOTHING,
            input: Input::default(),
            last: Instant::now(),
            display_ms: 0.0,
        })
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, e: ViewError) {
        self.result = Err(e);
        event_loop.exit();
    }

    /// One frame: camera input, a new render if anything changed, the panel, the display.
    fn redraw(&mut self, event_loop: &ActiveEventLoop) -> Result<(), ViewError> {
        let Some(r) = self.running.as_mut() else {
            return Ok(());
        };
        let s = &mut self.session;
        let now = Instant::now();
        let dt = (now - r.last).as_secs_f32().min(MAX_DT);
        r.last = now;
        match self.script.pop_front() {
            Some(step) => s.fly.apply(&step, SCRIPT_DT),
            None => s.fly.apply(&r.input.take(), dt),
        }
        let rendered = match s.update(&r.renderer, self.args.frames.is_some()) {
            Ok(rendered) => rendered,
            Err(e) if self.args.frames.is_some() => return Err(e),
            Err(e) => {
                s.status = e.to_string();
                false
            }
        };
        let start = Instant::now();
        r.update_picture(s);
        let (actions, paint) = r.run_ui(s);
        r.display.draw(r.renderer.context(), paint)?;
        r.display_ms = start.elapsed().as_secs_f64() * 1e3;
        r.input.reset |= actions.reset_camera;
        if let (true, Some(_), Some(f)) = (rendered, self.args.frames, &s.frame) {
            s.history
                .push((f.timings.clone(), f.render_ms, r.display_ms));
        }
        self.screenshot_asked |= actions.screenshot;
        if self.screenshot_asked && s.frame.is_some() {
            self.screenshot_asked = false;
            self.save_screenshot();
        }
        if actions.save_settings {
            self.save_settings();
        }
        if let Some(frames) = self.args.frames {
            self.frames += 1;
            if self.frames == frames {
                self.finish()?;
                event_loop.exit();
            }
        }
        Ok(())
    }

    /// A screenshot of the picture into the output folder.
    fn save_screenshot(&mut self) {
        let path = self.session.next_path("png");
        let saved = self.capture(false).and_then(|img| save_png(&img, &path));
        self.session.status = match saved {
            Ok(()) => format!("saved {}", path.display()),
            Err(e) => e.to_string(),
        };
    }

    /// The settings (K or the button) into the output folder.
    fn save_settings(&mut self) {
        let path = self.session.next_path("toml");
        self.session.status = match self.session.save_settings(&path) {
            Ok(()) => format!("saved {}", path.display()),
            Err(e) => e.to_string(),
        };
    }

    /// What the window shows: the picture, or with `window` the whole window.
    fn capture(&self, window: bool) -> Result<image::RgbImage, ViewError> {
        let r = self
            .running
            .as_ref()
            .ok_or(ViewError::Window("no window".into()))?;
        let canvas = r.display.canvas();
        let rect = if window {
            PixelRect {
                x: 0,
                y: 0,
                width: canvas.width(),
                height: canvas.height(),
            }
        } else {
            let [left, top, right, bottom] = r.picture_rect_px().map(|v| v.round().max(0.0) as u32);
            PixelRect {
                x: left,
                y: top,
                width: right.saturating_sub(left),
                height: bottom.saturating_sub(top),
            }
        };
        capture(r.renderer.context(), canvas, rect)
    }

    /// The end of a `--frames` run: the screenshot, the settings, the per-pass times.
    fn finish(&mut self) -> Result<(), ViewError> {
        let a = self.args;
        if let Some(path) = &a.screenshot {
            save_png(&self.capture(a.screenshot_window)?, path)?;
        }
        if let Some(path) = &a.save_settings {
            self.session.save_settings(path)?;
        }
        let s = &self.session;
        let adapter = self
            .running
            .as_ref()
            .map_or(String::new(), |r| r.renderer.renderer_label());
        let clock = s.frame.as_ref().map_or("", |f| f.clock.label());
        println!(
            "{}: {} frames of {}x{} on {}; ms per pass, median over the frames after the first \
             ({clock}; whole_frame: with the readbacks and metrics, and display: \
             wall clock):",
            s.scene.name, self.frames, s.width, s.height, adapter
        );
        for (name, ms) in s.median_timings() {
            println!("  {name:<16} {ms:>9.2}");
        }
        Ok(())
    }
}
