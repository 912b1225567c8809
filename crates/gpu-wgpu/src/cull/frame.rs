//! What the GPU culling passes share (`cull::tiled`, `cull::clustered`,
//! `cull::none`): their input ([`CullFrame`]: G-buffer positions on the GPU, camera, VPLs,
//! δ, interleaving), the input checks of the CPU cullers (`slc_cull`'s `pixel_count` and
//! `partition::check`), the uniform per-subregion tile grid and its [`GpuCullParams`], the
//! G-buffer positions the tile passes read, and the fault record they write.
use crate::cull::bounds::BoundsSettings;
use crate::cull::records::{GpuCullParams, GpuCullStatus, FRUSTUM_SLACK, MAX_K};
use crate::device::buffers::{read_back, upload};
use crate::device::context::{GpuContext, GpuError};
use crate::device::count::Count;
use crate::frame::raster::gbuffer::GpuGBuffer;
use crate::vpl::buffers::VplBuffers;
use crate::vpl::generate::GpuVpls;
use crate::vpl::records::GpuVpl;
use slc_bounds::StochasticParams;
use slc_core::{Camera, CullInput, Interleaving, Vpl, TILE_SIZE};
use slc_cull::{CullView, GlossyBound};

/// What every GPU culler reads: the G-buffer's world positions on the GPU and what culling
/// needs besides, from a CPU [`CullInput`] ([`CullFrame::upload`]) or a G-buffer rasterized
/// on the GPU ([`CullFrame::on_gpu`], read where it lies).
pub struct CullFrame<'a> {
    pub width: u32,
    pub height: u32,
    pub camera: &'a Camera,
    pub vpls: FrameVpls<'a>,
    /// δ of eq. (2).
    pub delta: f32,
    pub interleaving: Interleaving,
    /// `[x, y, z, 1]` per pixel, zero where the pixel has no sample.
    pub positions: wgpu::Buffer,
    /// The sub-pixel offset (s, t) of every sample: it lies on the ray through pixel
    /// (x + s, y + t). Only splatting depends on it (its rasterizer samples those rays).
    pub sample_offset: (f32, f32),
}

impl<'a> CullFrame<'a> {
    /// The culling view of the frame (the rotated, stretched space of section 6).
    pub fn view(&self) -> Result<CullView, GpuError> {
        CullView::new(self.camera, self.width, self.height)
            .map_err(|e| GpuError::Input(e.to_string()))
    }

    /// What the bounds of the frame's VPLs depend on, with `glossy` bounds for glossy VPLs
    /// (and as shapes too with `shapes`).
    pub fn bounds_settings(&self, glossy: GlossyBound, shapes: bool) -> BoundsSettings<'a> {
        BoundsSettings {
            camera: self.camera,
            width: self.width,
            height: self.height,
            delta: self.delta,
            glossy,
            interleaving: self.interleaving,
            shapes,
        }
    }

    /// `input` with its G-buffer positions uploaded; a G-buffer whose sample count does not
    /// match its size is an error (as the CPU cullers' first check). Its samples are taken
    /// to lie on the pixel centres' rays (`slc_cpu_ref::prepare` without a pass).
    pub fn upload(ctx: &GpuContext, input: &CullInput<'a>) -> Result<Self, GpuError> {
        let g = input.gbuffer;
        if u64::from(g.width) * u64::from(g.height) != g.samples.len() as u64 {
            return Err(GpuError::Input(format!(
                "G-buffer of {}x{} pixels has {} samples",
                g.width,
                g.height,
                g.samples.len()
            )));
        }
        let positions: Vec<[f32; 4]> = g
            .samples
            .iter()
            .map(|s| {
                s.as_ref()
                    .map_or([0.0; 4], |s| s.position.extend(1.0).to_array())
            })
            .collect();
        Ok(Self {
            width: g.width,
            height: g.height,
            camera: input.camera,
            vpls: FrameVpls::Cpu(input.vpls),
            delta: input.delta,
            interleaving: input.interleaving,
            positions: upload(ctx, "gbuffer positions", &positions)?,
            sample_offset: (0.5, 0.5),
        })
    }

    /// A G-buffer rendered on the GPU ([`crate::frame::raster::gbuffer::GbufferPass`]); its camera is
    /// the culling view.
    pub fn on_gpu(
        gbuffer: &'a GpuGBuffer,
        vpls: impl Into<FrameVpls<'a>>,
        delta: f32,
        interleaving: Interleaving,
    ) -> Self {
        Self {
            width: gbuffer.width,
            height: gbuffer.height,
            camera: &gbuffer.camera,
            vpls: vpls.into(),
            delta,
            interleaving,
            positions: gbuffer.positions.clone(),
            sample_offset: gbuffer.offset,
        }
    }
}

/// The VPLs a frame is culled and shaded with: on the CPU (validated and packed as
/// [`GpuVpl`]s by [`FrameVpls::records`]) or generated on the GPU
/// (`vpl::generate::VplGenPass`, complete records that never leave the device, counted there:
/// the passes size their buffers by [`FrameVpls::capacity`] and take the count into their
/// uniforms and dispatches with [`FrameVpls::count`], so nothing is read back but where the
/// count sizes them, `GpuVpls::fit_capacity`).
#[derive(Clone, Copy)]
pub enum FrameVpls<'a> {
    Cpu(&'a [Vpl]),
    Gpu(&'a GpuVpls),
}

impl FrameVpls<'_> {
    /// The most VPLs there can be: the number of CPU VPLs, or the capacity of the GPU's
    /// count (what buffers with a record per VPL hold).
    pub fn capacity(&self) -> usize {
        match self {
            Self::Cpu(v) => v.len(),
            Self::Gpu(v) => v.count.capacity as usize,
        }
    }

    /// Whether there can be no VPL.
    pub fn is_empty(&self) -> bool {
        self.capacity() == 0
    }

    /// The number of VPLs: the host's, or the count on the GPU.
    pub fn count(&self) -> Count {
        match self {
            Self::Cpu(v) => Count::Host(v.len() as u32),
            Self::Gpu(v) => Count::Gpu(v.count.clone()),
        }
    }

    /// The [`GpuVpl`] records on the GPU: the CPU's validated for δ = `delta` exactly as the
    /// CPU culler validates them (`GpuVpl::new`) and uploaded, or the GPU's own buffer.
    pub fn records(&self, ctx: &GpuContext, delta: f32) -> Result<VplBuffers, GpuError> {
        match self {
            Self::Cpu(vpls) => {
                let packed = vpls
                    .iter()
                    .enumerate()
                    .map(|(i, v)| GpuVpl::new(v, i, delta))
                    .collect::<Result<Vec<_>, _>>()?;
                VplBuffers::upload(ctx, "vpls", &packed)
            }
            Self::Gpu(vpls) => {
                // Generated VPLs are valid by construction (ξ in (0, 1)); δ is checked as
                // the CPU's records check it.
                StochasticParams::new(delta, 0.5).map_err(|e| GpuError::Input(e.to_string()))?;
                Ok(vpls.buffers.clone())
            }
        }
    }
}

impl<'a> From<&'a [Vpl]> for FrameVpls<'a> {
    fn from(v: &'a [Vpl]) -> Self {
        Self::Cpu(v)
    }
}

impl<'a> From<&'a Vec<Vpl>> for FrameVpls<'a> {
    fn from(v: &'a Vec<Vpl>) -> Self {
        Self::Cpu(v)
    }
}

impl<'a> From<&'a GpuVpls> for FrameVpls<'a> {
    fn from(v: &'a GpuVpls) -> Self {
        Self::Gpu(v)
    }
}

/// The validated sizes of a culling input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct CullSizes {
    pub pixels: u32,
    pub k: u32,
    pub vpl_count: u32,
}

/// The checks every CPU culler makes first (the sample count was checked when the frame was
/// made): pixel indices in u32, 1 <= K <= [`MAX_K`], a VPL capacity (`FrameVpls::capacity`)
/// in u32; and on an adapter that ends a shader's loops early ([`GpuContext::loop_budget`]),
/// the largest subregion's VPLs within what a tile's and a pixel's loops can walk
/// ([`GpuError::LoopBudget`]), reading the GPU's VPL count back (4 bytes) where the
/// capacity alone would refuse them.
pub(crate) fn check_input(ctx: &GpuContext, frame: &CullFrame) -> Result<CullSizes, GpuError> {
    let pixels = u32::try_from(u64::from(frame.width) * u64::from(frame.height)).map_err(|_| {
        GpuError::Input(format!(
            "G-buffer of {}x{} pixels exceeds u32 pixel indices",
            frame.width, frame.height
        ))
    })?;
    let k = frame.interleaving.k;
    if !(1..=MAX_K).contains(&k) {
        return Err(GpuError::Input(format!(
            "interleaving factor K = {k} must lie in 1..={MAX_K}"
        )));
    }
    let vpl_count = u32::try_from(frame.vpls.capacity())
        .map_err(|_| GpuError::Input(format!("{} VPLs exceed u32", frame.vpls.capacity())))?;
    // A tile walks its subregion's VPLs, and a pixel's list holds at most those: one
    // invocation's loops run at most once per VPL of the largest subregion, up to 18 more per
    // round of 256 (the one-pass tiled shading's; an eighth allows 32) and a few dozen
    // besides.
    if let Some(budget) = ctx.loop_budget {
        let iterations = |most: u64| most + most / 8 + 64;
        let most = largest_subregion(ctx, frame, |most| iterations(most) <= budget)?;
        ctx.check_loop_budget(
            || format!("culling and shading up to {most} VPLs in one of the {k}x{k} subregions"),
            iterations(most),
            "raise --interleave K (the VPLs per subregion fall as 1/K²), lower --rsm or shade \
             one of the --lobes",
        )?;
    }
    Ok(CullSizes {
        pixels,
        k,
        vpl_count,
    })
}

/// The most VPLs one of the frame's K² subregions can hold (`Interleaving::vpl_subregion`):
/// counted for CPU VPLs. GPU VPLs keep their ids on the GPU: a share of their number plus six
/// standard deviations of it (the subregions are drawn by a hash of the id; the number itself
/// where K = 1), first of the buffer's capacity and, where that share does not pass `fits`,
/// of their count read back (4 bytes).
pub(crate) fn largest_subregion(
    ctx: &GpuContext,
    frame: &CullFrame,
    fits: impl Fn(u64) -> bool,
) -> Result<u64, GpuError> {
    let interleaving = frame.interleaving;
    let subregions = interleaving.subregions();
    let share = |count: u64| match subregions {
        1 => count,
        _ => {
            let share = count as f64 / f64::from(subregions);
            (share + 6.0 * share.sqrt()).ceil() as u64
        }
    };
    match frame.vpls {
        FrameVpls::Cpu(vpls) => {
            let mut counts = vec![0u64; subregions as usize];
            for v in vpls {
                counts[interleaving.vpl_subregion(v.id) as usize] += 1;
            }
            Ok(counts.into_iter().max().unwrap_or(0))
        }
        FrameVpls::Gpu(vpls) => {
            let most = share(vpls.count.capacity as u64);
            if fits(most) {
                return Ok(most);
            }
            Ok(share(u64::from(vpls.read_count(ctx)?)))
        }
    }
}

/// The uniform per-subregion tile grid (`GpuCullParams`): `tiles_x` x `tiles_y` tiles of
/// [`TILE_SIZE`]² pixels per subregion image, sized for subregion 0 (the largest), and their
/// count over the K² subregions, with `lists_per_tile` lists each; an error when the list
/// ids (and one offset past them) do not fit u32.
pub(crate) fn tile_grid(
    frame: &CullFrame,
    lists_per_tile: u32,
) -> Result<(u32, u32, u32), GpuError> {
    let (w, h, k) = (frame.width, frame.height, frame.interleaving.k);
    let tiles_x = w.div_ceil(k).div_ceil(TILE_SIZE);
    let tiles_y = h.div_ceil(k).div_ceil(TILE_SIZE);
    let tiles = u64::from(k * k) * u64::from(tiles_x) * u64::from(tiles_y);
    let tile_count = u32::try_from(tiles)
        .ok()
        .filter(|_| u32::try_from(u64::from(lists_per_tile) * tiles + 1).is_ok())
        .ok_or_else(|| GpuError::Input(format!("{tiles} tiles exceed u32 list ids")))?;
    Ok((tiles_x, tiles_y, tile_count))
}

/// The tile passes' parameters for `frame` on the grid of [`tile_grid`], in `mode`.
pub(crate) fn cull_params(
    frame: &CullFrame,
    view: &CullView,
    (tiles_x, tiles_y, tile_count): (u32, u32, u32),
    mode: u32,
) -> GpuCullParams {
    let (width, height) = (frame.width, frame.height);
    let r = view.rotation();
    let tan_half = (0.5 * f64::from(frame.camera.yfov)).tan();
    let aspect = f64::from(width) / f64::from(height);
    GpuCullParams {
        rotation: [
            r.x_axis.extend(0.0).to_array(),
            r.y_axis.extend(0.0).to_array(),
            r.z_axis.extend(0.0).to_array(),
        ],
        eye: frame.camera.position.extend(0.0).to_array(),
        image: [
            (aspect * tan_half) as f32,
            tan_half as f32,
            width as f32,
            height as f32,
        ],
        width,
        height,
        k: frame.interleaving.k,
        tiles_x,
        tiles_y,
        tile_count,
        vpl_count: frame.vpls.capacity() as u32,
        frustum_slack: FRUSTUM_SLACK,
        mode,
        pad: [0; 3],
    }
}

/// Reads the fault record back and turns its faults into errors (as the CPU cullers: a
/// sample not in front of the camera, a bound beyond f32, entries beyond u32); returns the
/// total the last scan stored.
pub(crate) fn read_status(
    ctx: &GpuContext,
    status: &wgpu::Buffer,
    width: u32,
) -> Result<u32, GpuError> {
    let [state] = <[GpuCullStatus; 1]>::try_from(read_back(ctx, "cull status", status, 1)?)
        .map_err(|_| GpuError::Readback {
            label: "cull status".into(),
            message: "short read".into(),
        })?;
    if state.bad_pixel != u32::MAX {
        return Err(GpuError::Input(format!(
            "G-buffer sample of pixel ({}, {}) is not in front of the camera",
            state.bad_pixel % width,
            state.bad_pixel / width
        )));
    }
    if state.overflow_vpl != u32::MAX {
        return Err(GpuError::Input(format!(
            "the bound of VPL {} does not fit in f32 (extreme flux, delta or xi)",
            state.overflow_vpl
        )));
    }
    if state.total_overflow != 0 {
        return Err(GpuError::Input(
            "light-list entries exceed 32-bit offsets".into(),
        ));
    }
    Ok(state.total)
}
