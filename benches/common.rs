//! The built-in default scene and its VPLs, shared by the benchmarks.
use slc_core::frame::LobeSelection;
use slc_core::{builtin, Scene, Vpl};
use slc_cpu_ref::rsm::{trace_rsm, Rsm, TexelSample};
use slc_cpu_ref::vpls::generate_vpls;
use slc_cpu_ref::Tracer;

/// The default scene, its tracer and its RSMs of `rsm`² texels per face.
pub fn default_scene_maps(rsm: u32) -> (Scene, Tracer, Vec<Rsm>) {
    let scene = builtin("default").expect("built-in default scene");
    let tracer = Tracer::new(&scene);
    let maps = scene
        .lights
        .iter()
        .map(|l| trace_rsm(&scene, &tracer, l, rsm, TexelSample::Centre))
        .collect();
    (scene, tracer, maps)
}

/// The default scene, its tracer and its VPLs from an RSM of `rsm`² texels per face.
pub fn default_scene_vpls(rsm: u32) -> (Scene, Tracer, Vec<Vpl>) {
    let (scene, tracer, maps) = default_scene_maps(rsm);
    let vpls = generate_vpls(&maps, 0, LobeSelection::Both);
    (scene, tracer, vpls)
}
