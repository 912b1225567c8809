//! VPLs on the GPU: the counter-based RNG of `slc_core::rng` (`rng.wesl`; [`rng`] checks it
//! bit for bit against the CPU), the VPLs generated from the RSM texels and compacted by a
//! scan ([`generate`], `vpl_gen.wesl`) and the VPL record every later pass reads
//! (`gvpl.wesl`, [`records`]), over two storage buffers where one binding holds too few
//! ([`buffers`], `vpl_buffers.wesl`).
pub mod buffers;
pub mod generate;
pub mod records;
pub mod rng;
