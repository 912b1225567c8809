//! The device every pass runs on and what the passes share to use it: the context, its
//! faults as errors and its limits ([`context`]; the limits every pass needs:
//! [`required_limits`]), timestamp profiles ([`profiler`]), buffers, uploads, readbacks and
//! dispatch grids ([`buffers`]), counts left on the GPU and the indirect dispatches sized by
//! them ([`count`], `dispatch_args.wesl`), the prefix sum ([`scan`], `scan.wesl`) and records
//! over two bindings ([`split_buffers`]). `numbers.wesl` holds the f32 limits every kernel
//! shares.
pub mod buffers;
pub mod context;
pub mod count;
pub mod profiler;
pub mod required_limits;
pub mod scan;
pub mod split_buffers;

pub use context::{GpuContext, GpuError};

/// The size naga gives the WGSL struct `name` of `source`: what the layout tests of every
/// `records.rs` compare their Rust twins with.
#[cfg(test)]
pub(crate) fn wgsl_size(source: &str, name: &str) -> usize {
    use wgpu::naga;
    let module = naga::front::wgsl::parse_str(source).unwrap();
    let span = module.types.iter().find_map(|(_, ty)| match &ty.inner {
        naga::TypeInner::Struct { span, .. } if ty.name.as_deref() == Some(name) => Some(*span),
        _ => None,
    });
    span.unwrap_or_else(|| panic!("no struct {name}")) as usize
}
