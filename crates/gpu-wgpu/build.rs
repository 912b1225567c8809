//! Links each kernel's WESL modules (`src/**/*.wesl`) into one WGSL source with the `wesl`
//! crate, `OUT_DIR/kernels/<kernel>.wgsl`, which `kernel!` includes, and validates it with
//! naga, so that a shader error fails the build rather than a pipeline at run time:
//! - linked with mangled names, a name used without its `import` is undeclared;
//! - linked with the names as written (what the passes run, readable in a GPU debugger), two
//!   modules declaring one name clash.
//!
//! It also counts what each entry point binds and uses (naga's uses of each global, as wgpu
//! derives a pipeline's layout from them): storage and uniform buffers, textures and samplers
//! per stage, bind groups, workgroup sizes and workgroup memory. The most of each over every
//! entry point is what a device must allow, `OUT_DIR/kernels/limits.rs`
//! (`GpuContext::required_limits`).

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
    Kernel {
        name: "bounds",
        root: "cull::bounds",
        features: &[("box_bounds_written", true)],
    },
    k("partition", "cull::partition"),
    k("tile_depth", "cull::tiled::tile_depth"),
    k("tiled_cull", "cull::tiled::tiled_cull"),
    k("cluster_depth", "cull::clustered::cluster_depth"),
    k("clustered_cull", "cull::clustered::clustered_cull"),
    Kernel {
        name: "tight_cull",
        root: "cull::tight::tight_cull",
        features: &[("box_bounds_written", false)],
    },
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

/// What one entry point, or the most of every entry point, needs of a device: place i
/// bounds from below the `wgpu::Limits` field `NEEDS[i]`.
#[derive(Default)]
struct Needs([u32; 11]);

// The places of a `Needs`.
const STORAGE_BUFFERS: usize = 0;
const UNIFORM_BUFFERS: usize = 1;
const SAMPLED_TEXTURES: usize = 2;
const STORAGE_TEXTURES: usize = 3;
const SAMPLERS: usize = 4;
const BIND_GROUPS: usize = 5;
/// The workgroup's x, y and z sizes, then its invocations.
const WORKGROUP_SIZE: usize = 6;
const WORKGROUP_STORAGE: usize = 10;

/// The `wgpu::Limits` field of each place of a [`Needs`] (a place left out would name no
/// field, and the generated `limits.rs` would not compile).
const NEEDS: [&str; 11] = {
    let mut n = [""; 11];
    n[STORAGE_BUFFERS] = "max_storage_buffers_per_shader_stage";
    n[UNIFORM_BUFFERS] = "max_uniform_buffers_per_shader_stage";
    n[SAMPLED_TEXTURES] = "max_sampled_textures_per_shader_stage";
    n[STORAGE_TEXTURES] = "max_storage_textures_per_shader_stage";
    n[SAMPLERS] = "max_samplers_per_shader_stage";
    n[BIND_GROUPS] = "max_bind_groups";
    n[WORKGROUP_SIZE] = "max_compute_workgroup_size_x";
    n[WORKGROUP_SIZE + 1] = "max_compute_workgroup_size_y";
    n[WORKGROUP_SIZE + 2] = "max_compute_workgroup_size_z";
    n[WORKGROUP_SIZE + 3] = "max_compute_invocations_per_workgroup";
    n[WORKGROUP_STORAGE] = "max_compute_workgroup_storage_size";
    n
};

/// What each entry point of `module` needs ([`NEEDS`]): the globals it uses of each kind,
/// the bind groups up to the highest it uses, its workgroup size, and its workgroup memory
/// (each variable rounded up to 16 bytes, as WebGPU counts it).
fn needs(module: &naga::Module, info: &naga::valid::ModuleInfo) -> Vec<Needs> {
    let mut layouter = naga::proc::Layouter::default();
    layouter
        .update(module.to_ctx())
        .expect("the types of a validated module lay out");
    (module.entry_points.iter().enumerate())
        .map(|(i, entry)| {
            let uses = info.get_entry_point(i);
            let mut n = Needs::default();
            for (handle, global) in module.global_variables.iter() {
                if uses[handle].is_empty() {
                    continue;
                }
                let kind = match (global.space, &module.types[global.ty].inner) {
                    (naga::AddressSpace::Storage { .. }, _) => Some(STORAGE_BUFFERS),
                    (naga::AddressSpace::Uniform, _) => Some(UNIFORM_BUFFERS),
                    (_, naga::TypeInner::Image { class, .. }) => match class {
                        naga::ImageClass::Storage { .. } => Some(STORAGE_TEXTURES),
                        _ => Some(SAMPLED_TEXTURES),
                    },
                    (_, naga::TypeInner::Sampler { .. }) => Some(SAMPLERS),
                    (naga::AddressSpace::WorkGroup, _) => {
                        n.0[WORKGROUP_STORAGE] += layouter[global.ty].size.next_multiple_of(16);
                        None
                    }
                    _ => None,
                };
                if let Some(k) = kind {
                    n.0[k] += 1;
                }
                if let Some(binding) = &global.binding {
                    n.0[BIND_GROUPS] = n.0[BIND_GROUPS].max(binding.group + 1);
                }
            }
            if entry.stage == naga::ShaderStage::Compute {
                let [x, y, z] = entry.workgroup_size;
                n.0[WORKGROUP_SIZE..WORKGROUP_SIZE + 4].copy_from_slice(&[x, y, z, x * y * z]);
            }
            n
        })
        .collect()
}

fn main() {
    println!("cargo:rerun-if-changed=src");
    let out = std::path::Path::new(&std::env::var("OUT_DIR").expect("OUT_DIR")).join("kernels");
    std::fs::create_dir_all(&out).expect("kernels folder");
    let mut most = Needs::default();
    for kernel in KERNELS {
        let strict = link(kernel, wesl::ManglerKind::Escape);
        validate(kernel, &strict, "names mangled: every name imported");
        let source = link(kernel, wesl::ManglerKind::None);
        let (module, info) = validate(kernel, &source, "names as written: no clash");
        for n in needs(&module, &info) {
            for (most, n) in most.0.iter_mut().zip(n.0) {
                *most = (*most).max(n);
            }
        }
        std::fs::write(out.join(format!("{}.wgsl", kernel.name)), source).expect("kernel file");
    }
    let needs: String = (NEEDS.iter().zip(most.0))
        .map(|(name, n)| format!("    ({name:?}, {n}),\n"))
        .collect();
    let fields: String = NEEDS
        .iter()
        .map(|name| format!("        &mut limits.{name},\n"))
        .collect();
    let limits = format!(
        "/// Per `wgpu::Limits` field, the most any entry point of the kernels needs (build.rs).\n\
         pub(crate) const KERNEL_NEEDS: [(&str, u32); {n}] = [\n{needs}];\n\n\
         /// The fields of `limits` that [`KERNEL_NEEDS`] names, in its order.\n\
         pub(crate) fn kernel_fields(limits: &mut wgpu::Limits) -> [&mut u32; {n}] {{\n    \
         [\n{fields}    ]\n}}\n",
        n = NEEDS.len()
    );
    std::fs::write(out.join("limits.rs"), limits).expect("limits file");
}
