//! Screenshots: a rectangle of the canvas (what the window shows) read back as an sRGB PNG.
use super::display::CANVAS_FORMAT;
use super::ViewError;
use image::RgbImage;
use slc_gpu_wgpu::device::buffers::read_back;
use slc_gpu_wgpu::GpuContext;
use std::path::Path;

/// A pixel rectangle of the canvas: left, top, width, height.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelRect {
    pub x: u32,
    pub y: u32,
    pub width: u32,
    pub height: u32,
}

/// Reads `rect` of `canvas` back (clipped to the canvas).
pub fn capture(
    ctx: &GpuContext,
    canvas: &wgpu::Texture,
    rect: PixelRect,
) -> Result<RgbImage, ViewError> {
    debug_assert_eq!(canvas.format(), CANVAS_FORMAT);
    let x = rect.x.min(canvas.width().saturating_sub(1));
    let y = rect.y.min(canvas.height().saturating_sub(1));
    let width = rect.width.min(canvas.width() - x).max(1);
    let height = rect.height.min(canvas.height() - y).max(1);
    let row = (4 * width).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let size = u64::from(row) * u64::from(height);
    let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("screenshot"),
        size,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture: canvas,
            mip_level: 0,
            origin: wgpu::Origin3d { x, y, z: 0 },
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    ctx.queue.submit([encoder.finish()]);
    let bytes: Vec<u8> = read_back(ctx, "screenshot", &buffer, size as usize)?;
    Ok(RgbImage::from_fn(width, height, |px, py| {
        let i = (py * row + 4 * px) as usize;
        image::Rgb([bytes[i], bytes[i + 1], bytes[i + 2]])
    }))
}

/// Writes `image` as a PNG at `path`.
pub fn save_png(image: &RgbImage, path: &Path) -> Result<(), ViewError> {
    image.save(path).map_err(|e| ViewError::Write {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}
