//! VPL generation in compute (`vpl_gen.wesl`), GPU twin of
//! `slc_cpu_ref::vpls::generate_vpls`: one diffuse VPL (id 2k, where kd > 0) and one glossy
//! VPL (id 2k + 1, where the specular layer reflects) per lit texel k of the concatenated
//! maps, ξ = `rng::vpl_xi(seed, id)` (paper eq. 3) from `rng.wesl`, compacted in the
//! CPU's order by a count pass, an exclusive scan (`device::scan`) and a write pass, in one
//! submission. Nothing is read back: the count stays on the GPU ([`GpuCount`], the scan's
//! total), the VPL buffers hold the most VPLs the maps can make (one per texel and lobe
//! selected: a 1024² map's glossy VPLs fill one 128 MiB binding exactly, both lobes' two
//! of them, [`VplBuffers`]), and the
//! passes after it take the count from there (`device::count`).
use crate::cull::records::{GpuCullStatus, CULL_COUNT, CULL_WRITE};
use crate::device::buffers::{output, uniform, upload, Grid};
use crate::device::context::{GpuContext, GpuError};
use crate::device::count::GpuCount;
use crate::device::scan::ScanPass;
use crate::frame::light::rsm::GpuRsm;
use crate::vpl::buffers::VplBuffers;
use crate::vpl::records::GpuVplGenParams;
use crate::vpl::records::{anisotropy_from_gpu, GpuVpl, FRESNEL_DIELECTRIC, LOBE_DIFFUSE};
use glam::Vec3;
use slc_bounds::{fresnel::cos_theta_h_max, Brdf, Fresnel};
use slc_core::frame::LobeSelection;
use slc_core::{Vpl, VplLobe};

/// The kernel of `vpl_gen.wesl`, linked with what it imports (build.rs).
pub(crate) const SOURCE: &str = kernel!("vpl_gen");
const WORKGROUP: u32 = 64;

/// Which lobes become VPLs (`slc_cpu_ref::LobeSelection`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VplLobes {
    Both,
    Diffuse,
    Glossy,
}

impl From<LobeSelection> for VplLobes {
    fn from(lobes: LobeSelection) -> Self {
        match lobes {
            LobeSelection::Both => VplLobes::Both,
            LobeSelection::Diffuse => VplLobes::Diffuse,
            LobeSelection::Glossy => VplLobes::Glossy,
        }
    }
}

impl VplLobes {
    fn mask(self) -> u32 {
        match self {
            VplLobes::Both => 3,
            VplLobes::Diffuse => 1,
            VplLobes::Glossy => 2,
        }
    }

    /// How many VPLs a texel makes at most: one per lobe selected.
    pub fn per_texel(self) -> u32 {
        self.mask().count_ones()
    }
}

/// VPLs on the GPU in the [`GpuVpl`] layout the bounds and shading passes read, complete:
/// the bound factor `geometric_tilt.w` is formed in f32 (`vpl_bound_factor` in
/// `vpl_gen.wesl`), never below [`GpuVpl::new`]'s. They stay on the GPU for a frame,
/// and so does their number; [`GpuVpls::read_count`] and [`GpuVpls::read_back`] bring them to
/// the CPU where something there needs them.
pub struct GpuVpls {
    /// The VPLs in the CPU's order, then unused records: room for one VPL per texel and lobe
    /// (the count's capacity, unless [`GpuVpls::fit_capacity`] lowered it to the count).
    pub buffers: VplBuffers,
    /// The number of VPLs (`GpuCullStatus::total` of the generation's scan).
    pub count: GpuCount,
}

impl GpuVpls {
    /// The number of VPLs, read back (12 bytes, `vpl count`).
    pub fn read_count(&self, ctx: &GpuContext) -> Result<u32, GpuError> {
        self.count.read(ctx, "vpl count")
    }

    /// Where the count's capacity exceeds `most`, the VPLs the passes after can keep per-VPL
    /// records for, reads the count back (12 bytes, a wait for the generation) and makes it
    /// the capacity, by which those passes size their per-VPL buffers: a 1024² RSM of both
    /// lobes has room for 2,097,152 VPLs, whose bounds of 80 bytes would take 160 MiB, where
    /// Sponza makes 1,647,184 (126 MiB). Other frames read nothing. Returns the count where
    /// it was read.
    pub fn fit_capacity(&mut self, ctx: &GpuContext, most: usize) -> Result<Option<u32>, GpuError> {
        if self.count.capacity as usize <= most {
            return Ok(None);
        }
        self.count.capacity = self.read_count(ctx)?;
        Ok(Some(self.count.capacity))
    }

    /// The VPLs as `slc_core::Vpl`s, in the CPU's order.
    pub fn read_back(&self, ctx: &GpuContext) -> Result<Vec<Vpl>, GpuError> {
        let count = self.read_count(ctx)?;
        let raw = self.buffers.read_back(ctx, count as usize)?;
        Ok(raw.iter().map(unpack).collect())
    }
}

fn unpack(v: &GpuVpl) -> Vpl {
    let v3 = |a: [f32; 4]| Vec3::new(a[0], a[1], a[2]);
    let fresnel = if v.fresnel == FRESNEL_DIELECTRIC {
        Fresnel::Dielectric(v.omega_i_eta[3])
    } else {
        Fresnel::Schlick(Vec3::from(v.f0))
    };
    Vpl {
        position: v3(v.position_xi),
        normal: v3(v.normal_alpha),
        geometric_normal: v3(v.geometric_tilt),
        omega_i: v3(v.omega_i_eta),
        flux: Vec3::from(v.flux),
        brdf: Brdf {
            kd: Vec3::from(v.kd),
            fresnel,
            alpha: v.normal_alpha[3],
            anisotropy: anisotropy_from_gpu(v.anisotropy),
        },
        lobe: if v.lobe == LOBE_DIFFUSE {
            VplLobe::Diffuse
        } else {
            VplLobe::Glossy
        },
        id: v.id,
        xi: v.position_xi[3],
    }
}

/// The byte offset of `GpuCullStatus::total`, where the scan leaves the VPL count.
const STATUS_TOTAL: u64 = std::mem::offset_of!(GpuCullStatus, total) as u64;

/// The compiled generation and scan pipelines.
pub struct VplGenPass {
    pipeline: wgpu::ComputePipeline,
    scan: ScanPass,
}

impl VplGenPass {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        ctx.scoped("vpl generation pipelines", || {
            Ok(Self {
                pipeline: ctx.compute_pipeline("vpl generation", SOURCE),
                scan: ScanPass::new(ctx),
            })
        })
    }

    /// The VPLs of `maps` (one per light, in light order) with ξ from `seed`. Errors when the
    /// texels exceed 32-bit VPL ids, on buffers beyond the device's limits and on device
    /// faults.
    pub fn generate(
        &self,
        ctx: &GpuContext,
        maps: &[GpuRsm],
        seed: u32,
        lobes: VplLobes,
    ) -> Result<GpuVpls, GpuError> {
        let total: usize = maps.iter().map(GpuRsm::texel_count).sum();
        let total = u32::try_from(total)
            .ok()
            .filter(|t| t.checked_mul(2).is_some())
            .ok_or_else(|| GpuError::Input(format!("{total} RSM texels exceed 32-bit VPL ids")))?;
        let counts = output::<u32>(ctx, "vpl offsets", total as usize + 1)?;
        let status = upload(ctx, "vpl status", &[GpuCullStatus::CLEAR])?;
        let passes = |mode| -> Result<Vec<(wgpu::Buffer, Grid, &GpuRsm)>, GpuError> {
            let mut base = 0;
            let mut out = Vec::with_capacity(maps.len());
            for map in maps {
                let texel_count = map.texel_count() as u32;
                let params = GpuVplGenParams {
                    texel_count,
                    base,
                    seed,
                    lobes: lobes.mask(),
                    mode,
                    cos_h_max: cos_theta_h_max(1.0, 0.0),
                    pad: [0; 2],
                };
                let grid = Grid::for_items(ctx, u64::from(texel_count), WORKGROUP)?;
                out.push((uniform(ctx, "vpl generation params", &params), grid, map));
                base += texel_count;
            }
            Ok(out)
        };
        let count_passes = passes(CULL_COUNT)?;
        let write_passes = passes(CULL_WRITE)?;
        let capacity = lobes.per_texel() * total;
        let vpls = VplBuffers::output(ctx, "vpls", capacity as usize)?;
        let no_vpls = [
            output::<GpuVpl>(ctx, "no vpls", 1)?,
            output::<GpuVpl>(ctx, "no vpls", 1)?,
        ];
        ctx.submit("vpl generation", |encoder| {
            for (params, grid, map) in &count_passes {
                ctx.encode_dispatch(
                    encoder,
                    "vpl count",
                    &self.pipeline,
                    &[params, &map.texels, &counts, &no_vpls[0], &no_vpls[1]],
                    *grid,
                );
            }
            self.scan.encode(ctx, encoder, &counts, total, &status)?;
            for (params, grid, map) in &write_passes {
                ctx.encode_dispatch(
                    encoder,
                    "vpl write",
                    &self.pipeline,
                    &[params, &map.texels, &counts, &vpls.low, &vpls.high],
                    *grid,
                );
            }
            Ok(())
        })?;
        Ok(GpuVpls {
            buffers: vpls,
            count: GpuCount {
                buffer: status,
                offset: STATUS_TOTAL,
                capacity,
            },
        })
    }
}
