//! What slc's front ends share beyond the renderer API: the result folder (atomic, locked),
//! the memory check before work, the provenance and `report.json` of a frame, the images a
//! frame is written as (EXR, layered EXR, sRGB PNG), the all-VPL reference, repeated timings,
//! progress bars, the backends and their refusals. The `slc` command and the Python package (`python/`) both write and return
//! reports and images through it.
pub mod backends;
pub mod cpu_frames;
pub mod layers_exr;
pub mod limits;
pub mod out_dir;
pub mod output;
pub mod progress;
pub mod provenance;
pub mod reference;
pub mod repeat;
pub mod report;
