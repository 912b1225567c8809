//! The GGX specular lobe's SG fit on the GPU: `slc_bounds::sg::specular_table` uploaded as the
//! uniform `specular_table` of `specular_table.wesl`, bound at [`BINDING`] by every
//! entry point that builds an SG receiver (`make_surface` in `sg_surface.wesl`).
use crate::device::context::GpuContext;
use slc_bounds::sg::specular_table::TABLE;

/// The binding number of the table in group 0 (above every other binding of the VSGL shaders).
pub(crate) const BINDING: u32 = 20;

/// The table as a uniform buffer (8,976 bytes).
pub(crate) fn buffer(ctx: &GpuContext) -> wgpu::Buffer {
    let bytes: &[u8] = bytemuck::cast_slice(&TABLE[..]);
    let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("specular fit table"),
        size: bytes.len() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    ctx.queue.write_buffer(&buffer, 0, bytes);
    buffer
}

#[cfg(test)]
mod tests {
    use super::*;
    use slc_bounds::sg::{ALPHA_STEPS, VIEW_STEPS};

    /// The WGSL declaration has the Rust table's shape and binding.
    #[test]
    fn wgsl_declares_the_rust_table() {
        let wgsl = include_str!("specular_table.wesl");
        for line in [
            format!("const SPECULAR_ALPHA_STEPS: u32 = {ALPHA_STEPS}u;"),
            format!("const SPECULAR_VIEW_STEPS: u32 = {VIEW_STEPS}u;"),
            format!(
                "@group(0) @binding({BINDING}) var<uniform> specular_table: array<vec4<f32>, {}>;",
                TABLE.len()
            ),
        ] {
            assert!(wgsl.lines().any(|l| l == line), "missing: {line}");
        }
    }
}
