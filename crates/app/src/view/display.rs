//! The window's pixels: egui (panel and the rendered frame) is drawn into an offscreen
//! canvas, which is blitted to the window's surface and read back for screenshots, so a
//! screenshot is exactly what the window shows.
use super::ViewError;
use slc_gpu_wgpu::GpuContext;
use std::sync::Arc;
use winit::window::Window;

/// The canvas format: gamma-space RGBA, what egui-wgpu prefers to draw into.
pub const CANVAS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// One frame of egui output, tessellated.
pub struct Paint {
    pub jobs: Vec<egui::ClippedPrimitive>,
    pub textures: egui::TexturesDelta,
    pub pixels_per_point: f32,
}

/// The surface of the window, the canvas, and the renderers that draw them.
pub struct Display {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    /// The non-sRGB view of the surface texture (the canvas holds gamma-space values).
    view_format: wgpu::TextureFormat,
    canvas: wgpu::Texture,
    egui: egui_wgpu::Renderer,
    blitter: wgpu::util::TextureBlitter,
}

impl Display {
    /// Opens the adapter that can present to `window`, a device with its limits (and
    /// timestamp queries where it has them) and the display on that device.
    pub fn open(window: Arc<Window>) -> Result<(Self, GpuContext), ViewError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let surface = instance
            .create_surface(Arc::clone(&window))
            .map_err(|e| ViewError::NoAdapter(format!("no surface for the window: {e}")))?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            compatible_surface: Some(&surface),
            ..Default::default()
        }))
        .map_err(|e| ViewError::NoAdapter(e.to_string()))?;
        let timestamps = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("slc view"),
            required_features: timestamps,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| slc_gpu_wgpu::GpuError::RequestDevice {
            adapter: adapter.get_info().name,
            reason: e.to_string(),
        })?;
        let ctx = GpuContext::from_device(device.clone(), queue, &adapter.get_info());
        let size = window.inner_size();
        let mut config = surface
            .get_default_config(&adapter, size.width.max(1), size.height.max(1))
            .ok_or_else(|| ViewError::Surface("the adapter cannot present to the window".into()))?;
        let view_format = config.format.remove_srgb_suffix();
        config.view_formats = vec![view_format];
        config.present_mode = wgpu::PresentMode::AutoVsync;
        surface.configure(&device, &config);
        let display = Self {
            canvas: canvas(&device, config.width, config.height),
            egui: egui_wgpu::Renderer::new(&device, CANVAS_FORMAT, Default::default()),
            blitter: wgpu::util::TextureBlitter::new(&device, view_format),
            surface,
            config,
            view_format,
        };
        Ok((display, ctx))
    }

    /// Follows the window's new size in pixels.
    pub fn resize(&mut self, device: &wgpu::Device, width: u32, height: u32) {
        if width == 0 || height == 0 {
            return;
        }
        self.config.width = width;
        self.config.height = height;
        self.surface.configure(device, &self.config);
        self.canvas = canvas(device, width, height);
    }

    /// The canvas: what the window shows after [`Display::draw`].
    pub fn canvas(&self) -> &wgpu::Texture {
        &self.canvas
    }

    /// Draws `paint` into the canvas and presents the canvas in the window.
    pub fn draw(&mut self, ctx: &GpuContext, paint: Paint) -> Result<(), ViewError> {
        let (device, queue) = (&ctx.device, &ctx.queue);
        for (id, deltas) in &paint.textures.set {
            for delta in deltas {
                self.egui.update_texture(device, queue, *id, delta);
            }
        }
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [self.config.width, self.config.height],
            pixels_per_point: paint.pixels_per_point,
        };
        let mut encoder = device.create_command_encoder(&Default::default());
        let extra = self
            .egui
            .update_buffers(device, queue, &mut encoder, &paint.jobs, &screen);
        let canvas = self.canvas.create_view(&Default::default());
        {
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("egui"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &canvas,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            self.egui
                .render(&mut pass.forget_lifetime(), &paint.jobs, &screen);
        }
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => Some(t),
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(device, &self.config);
                None
            }
            // Skipped this frame (the canvas is still drawn, so screenshots work).
            _ => None,
        };
        if let Some(frame) = &frame {
            let target = frame.texture.create_view(&wgpu::TextureViewDescriptor {
                format: Some(self.view_format),
                ..Default::default()
            });
            self.blitter.copy(device, &mut encoder, &canvas, &target);
        }
        queue.submit(extra.into_iter().chain([encoder.finish()]));
        if let Some(frame) = frame {
            queue.present(frame);
        }
        for id in &paint.textures.free {
            self.egui.free_texture(id);
        }
        ctx.wait()?;
        Ok(())
    }
}

fn canvas(device: &wgpu::Device, width: u32, height: u32) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("canvas"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: CANVAS_FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}
