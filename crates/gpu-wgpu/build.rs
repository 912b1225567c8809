//! Links each kernel's WESL modules (`src/**/*.wesl`) into one WGSL source with the `wesl`
//! crate, `OUT_DIR/kernels/<kernel>.wgsl`, which `kernel!` includes, and validates it with
//! naga, so that a shader error fails the build rather than a pipeline at run time:
//! - linked with mangled names, a name used without its `import` is undeclared;
//! - linked with the names as written (what the passes run, readable in a GPU debugger), two
//!   modules declaring one name clash.
//!
//! It also counts the storage buffers each entry point binds (naga's uses of each global, as
//! wgpu derives a pipeline's layout from them): the most of any is the limit a device must
//! allow per shader stage, `OUT_DIR/kernels/limits.rs` (`GpuContext::required_limits`).

/// A kernel: its artifact name, its root module (the one with the entry points) and the
/// WESL features it is linked with (`@if(...)`).
struct Kernel {
    name: &'static str,
    root: &'static str,
    features: &'static [(&'static str, bool)],
}

const fn k(name: &'static str, root: &'static str) -> Kernel {
    Kernel {
        name,
        root,
        features: &[],
    }
}

const KERNELS: &[Kernel] = &[
    k("dispatch_args", "device::dispatch_args"),
    k("scan", "device::scan"),
    k("visibility", "frame::raster::visibility"),
    k("gbuffer", "frame::raster::gbuffer"),
    k("rsm", "frame::light::rsm"),
    k("direct", "frame::light::direct"),
    k("bilateral", "frame::denoise::bilateral"),
    k("rng_eval", "vpl::rng_eval"),
    k("vpl_gen", "vpl::vpl_gen"),
    k("bounds", "cull::bounds"),
    k("partition", "cull::partition"),
    k("tile_depth", "cull::tiled::tile_depth"),
    k("tiled_cull", "cull::tiled::tiled_cull"),
    k("cluster_depth", "cull::clustered::cluster_depth"),
    k("clustered_cull", "cull::clustered::clustered_cull"),
    k("tight_cull", "cull::tight::tight_cull"),
    k("none_cull", "cull::none::none_cull"),
    k("binned_footprint", "cull::binned::binned_footprint"),
    k("binned_tiles", "cull::binned::binned_tiles"),
    k("binned_bins", "cull::binned::binned_bins"),
    k("binned_cull", "cull::binned::binned_cull"),
    k("raster_args", "cull::raster::raster_args"),
    k("splat", "cull::raster::splat"),
    k("splat_resolve", "cull::raster::splat_resolve"),
    k("cluster_shell", "cull::raster::cluster_shell"),
    k("cluster_fill", "cull::raster::cluster_fill"),
    k("node_shade", "cull::raster::node_shade"),
    k("shade", "shade::shade"),
    Kernel {
        name: "tiled_shade",
        root: "shade::tiled_shade",
        features: &[("subgroups", false)],
    },
    Kernel {
        name: "tiled_shade_subgroups",
        root: "shade::tiled_shade",
        features: &[("subgroups", true)],
    },
    k("vsgl_build", "vsgl::build::vsgl_build"),
    k("vsgl_shade", "vsgl::shade::vsgl_shade"),
    k("ism", "vsgl::ism::ism"),
    k("ism_fill", "vsgl::ism::ism_fill"),
];

fn link(kernel: &Kernel, mangler: wesl::ManglerKind) -> String {
    let mut compiler = wesl::Wesl::new("src");
    compiler.set_mangler(mangler);
    for &(feature, on) in kernel.features {
        compiler.set_feature(feature, on);
    }
    let root = format!("package::{}", kernel.root);
    let path = root
        .parse()
        .unwrap_or_else(|e| panic!("module path {root}: {e}"));
    match compiler.compile(&path) {
        Ok(linked) => linked.to_string(),
        Err(e) => panic!("kernel {}: WESL error: {e}", kernel.name),
    }
}

fn validate(kernel: &Kernel, source: &str, what: &str) -> (naga::Module, naga::valid::ModuleInfo) {
    let module = naga::front::wgsl::parse_str(source).unwrap_or_else(|e| {
        panic!(
            "kernel {} ({what}): {}\n{source}",
            kernel.name,
            e.emit_to_string(source)
        )
    });
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("kernel {} ({what}): {e:?}", kernel.name));
    (module, info)
}

/// The storage buffers each entry point of `module` uses, with its name.
fn storage_buffers<'a>(
    module: &'a naga::Module,
    info: &'a naga::valid::ModuleInfo,
) -> impl Iterator<Item = (usize, &'a str)> + 'a {
    module.entry_points.iter().enumerate().map(|(i, entry)| {
        let uses = info.get_entry_point(i);
        let count = (module.global_variables.iter())
            .filter(|(handle, global)| {
                matches!(global.space, naga::AddressSpace::Storage { .. })
                    && !uses[*handle].is_empty()
            })
            .count();
        (count, entry.name.as_str())
    })
}

fn main() {
    println!("cargo:rerun-if-changed=src");
    let out = std::path::Path::new(&std::env::var("OUT_DIR").expect("OUT_DIR")).join("kernels");
    std::fs::create_dir_all(&out).expect("kernels folder");
    let mut most = (0, String::new());
    for kernel in KERNELS {
        let strict = link(kernel, wesl::ManglerKind::Escape);
        validate(kernel, &strict, "names mangled: every name imported");
        let source = link(kernel, wesl::ManglerKind::None);
        let (module, info) = validate(kernel, &source, "names as written: no clash");
        for (count, entry) in storage_buffers(&module, &info) {
            if count > most.0 {
                most = (count, format!("{}'s {entry}", kernel.name));
            }
        }
        std::fs::write(out.join(format!("{}.wgsl", kernel.name)), source).expect("kernel file");
    }
    let limits = format!(
        "/// The most storage buffers one entry point of the kernels binds ({}), counted by \
         build.rs.\npub(crate) const KERNEL_STORAGE_BUFFERS: u32 = {};\n",
        most.1, most.0
    );
    std::fs::write(out.join("limits.rs"), limits).expect("limits file");
}
