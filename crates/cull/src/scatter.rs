//! One VPL of the `binned` strategy: its own bound (the section-6 sphere, or the GGX spheroid
//! of eq. 12-15, grown by `BOUND_SLACK`: the bound every strategy culls with), the pixels of
//! its subregion's image it may cover ([`crate::footprint`]) and the test each of those
//! pixels makes.
use crate::footprint::{footprint, Bound, Footprint, ScreenMap};
use crate::reach::{reflects_nothing, SIGN_MARGIN};
use crate::rounding::{down, up};
use crate::view::CullView;
use crate::vpl_bounds::{GlossyBound, LocalBound};
use glam::{DVec3, Vec3};
use slc_bounds::lanes::{splat_all, Lanes8};
use slc_bounds::StochasticParams;
use slc_core::{CullError, Interleaving, Subregions, Vpl};

/// The largest value of a pixel's coordinates in the bound's unit ball that still counts
/// as inside: 1 plus 1e-6 for the f64 rounding of the test (about 1e-16 of its terms, which
/// the eccentricity 1/(2α) of the sharpest spheroid raises at most 10^6-fold).
pub(crate) const LIMIT: f64 = 1.0 + 1e-6;

/// A VPL's bound as a pixel tests it, in world axes relative to q, in f64: the sign of ωo·n
/// at the VPL (eq. 4: I(ωo) = 0 behind its surface), then the spheroid `{c + R diag(r_u, r,
/// r) w : |w| <= 1}` (or sphere) through its axis ω_u: with e = x − c and t = e·ω_u,
/// |e − t ω_u|²/r² + t²/r_u² <= 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PixelTest {
    pub position: DVec3,
    pub normal: DVec3,
    pub center: DVec3,
    pub axis: DVec3,
    /// The semi-axes r_u (along ω_u) and r (across), and their inverse squares: set together
    /// by [`Self::new`] only.
    along: f64,
    across: f64,
    inv_along_sq: f64,
    inv_across_sq: f64,
}

impl PixelTest {
    /// The test of a VPL at `position` with unit `normal` whose bound is the spheroid (or
    /// sphere) centred at `center` relative to it, of semi-axes `along` its unit `axis` and
    /// `across` it.
    pub(crate) fn new(
        position: DVec3,
        normal: DVec3,
        center: DVec3,
        axis: DVec3,
        along: f64,
        across: f64,
    ) -> Self {
        Self {
            position,
            normal,
            center,
            axis,
            along,
            across,
            inv_along_sq: (along * along).recip(),
            inv_across_sq: (across * across).recip(),
        }
    }

    /// The semi-axes `[r_u, r]`: along ω_u and across it.
    #[inline]
    pub(crate) fn semi_axes(&self) -> [f64; 2] {
        [self.along, self.across]
    }

    /// Whether f32 lanes can hold the bound without overflow or losing it: semi-axes within
    /// [1e-18, 1e18] and the centre at most 1e18 from the VPL (the domain of the lane tests
    /// of `pixel_rows` and `cells`).
    pub(crate) fn fits_f32(&self) -> bool {
        let domain = 1e-18..=1e18;
        domain.contains(&self.along.min(self.across))
            && domain.contains(&self.along.max(self.across))
            && self.center.length() <= 1e18
    }

    /// Their inverse squares `[1/r_u², 1/r²]`, as the test forms them.
    #[inline]
    pub(crate) fn inverse_squares(&self) -> [f64; 2] {
        [self.inv_along_sq, self.inv_across_sq]
    }

    /// Whether the pixel whose G-buffer point is `x` may hold a pair with p > ξ: not behind
    /// the VPL by more than [`SIGN_MARGIN`] (where the shader's own f32 cosine, from the
    /// correctly rounded x − q, is negative too) and inside the bound. False where `x` is
    /// NaN. Both conditions are formed and combined without a branch: about one pixel in
    /// eight passes, and which side of the VPL a pixel lies on is not predictable.
    #[inline]
    pub(crate) fn contains(&self, x: Vec3) -> bool {
        let d = x.as_dvec3() - self.position;
        let cos = self.normal.dot(d);
        let behind =
            (cos < 0.0) & (cos * cos > f64::from(SIGN_MARGIN * SIGN_MARGIN) * d.length_squared());
        let e = d - self.center;
        let t = e.dot(self.axis);
        let inside = (e - t * self.axis).length_squared() * self.inv_across_sq
            + t * t * self.inv_along_sq
            <= LIMIT;
        !behind & inside
    }
}

/// A [`PixelTest`]'s VPL and bound rounded to f32, as the lane tests take them (`pixel_rows`'
/// filter and the cells' test): the VPL's position q (an f32 point already) and normal n,
/// the bound's centre c relative to q and its axis ω_u. `Frame<f32>` holds one VPL's values,
/// `Frame<L>` the same in every lane of `L`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame<R = f32> {
    pub q: [R; 3],
    pub normal: [R; 3],
    pub center: [R; 3],
    pub axis: [R; 3],
}

impl Frame {
    pub(crate) fn of(test: &PixelTest) -> Self {
        Self {
            q: test.position.as_vec3().to_array(),
            normal: test.normal.as_vec3().to_array(),
            center: test.center.as_vec3().to_array(),
            axis: test.axis.as_vec3().to_array(),
        }
    }

    #[inline(always)]
    pub(crate) fn lanes<L: Lanes8>(&self) -> Frame<L> {
        Frame {
            q: splat_all(&self.q),
            normal: splat_all(&self.normal),
            center: splat_all(&self.center),
            axis: splat_all(&self.axis),
        }
    }
}

/// A VPL that may cover pixels: its number, its subregion, its test and the rectangle of
/// its subregion image's pixels `[i0, i1] x [j0, j1]` (inclusive) where its bound may lie.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Scattered {
    pub index: u32,
    pub subregion: [u32; 2],
    pub test: PixelTest,
    pub pixels: [u32; 4],
}

/// What the scatter reads besides the VPLs: the view as the footprint maps it, the image
/// and the G-buffer samples' extremes.
pub(crate) struct Screen {
    pub map: ScreenMap<f32>,
    /// The interleaving's subregions of this image.
    pub subregions: Subregions,
    /// The eye, from which the bounds' centres are taken.
    pub eye: Vec3,
    /// How far (in screen pixels) any sample's projection lies outside its own pixel
    /// (negative: inside it by at least that much).
    pub stray: f64,
    /// A footprint's rectangle covers no sample where it ends before `edges[0]` or starts
    /// after `edges[1]` (x, y): the image's pixels grown by the stray and a pixel, rounded
    /// outwards.
    pub edges: [[f32; 2]; 2],
}

impl Screen {
    /// The scatter of a `width` x `height` image seen by `view` whose samples stray up to
    /// `stray` pixels outside their own (below 0: inside it by at least −`stray`) and lie no
    /// nearer than `near`. Errors on an interleaving factor K of 0 or with K² beyond u32.
    pub(crate) fn new(
        view: &CullView,
        width: u32,
        height: u32,
        interleaving: Interleaving,
        stray: f64,
        near: f64,
    ) -> Result<Self, CullError> {
        let rotation = view.rotation();
        let (scale, offset) = view.screen_map();
        let k = interleaving.k;
        let subregions = Subregions::new(interleaving, width, height)
            .ok_or_else(|| CullError::Input(format!("interleaving factor K = {k} out of range")))?;
        Ok(Self {
            map: ScreenMap {
                rows: [0, 1, 2].map(|i| rotation.row(i).to_array()),
                scale: scale.map(|v| v as f32),
                offset: offset.map(|v| v as f32),
                // Rounded down: no sample lies nearer.
                near: down(near),
            },
            subregions,
            eye: view.eye(),
            stray,
            edges: [
                [-1.0, -1.0].map(|e| down(e - stray)),
                [width, height].map(|n| up(f64::from(n) + stray + 1.0)),
            ],
        })
    }

    /// VPL `index` for the roulette's δ, `None` where it covers no pixel (it reflects
    /// nothing, lies nearer than every sample or outside the image). Errors on a VPL outside
    /// the domain of slc-bounds, as every bound-based strategy does. The bound is slc-bounds'
    /// own (`LocalBound`): this is the path of every VPL the lanes do not take
    /// (`crate::vpl_lanes`).
    pub(crate) fn scatter(
        &self,
        vpl: &Vpl,
        index: u32,
        delta: f32,
    ) -> Result<Option<Scattered>, CullError> {
        if !(vpl.position.is_finite() && vpl.omega_i.is_finite()) {
            return Err(CullError::Input(format!(
                "VPL {index} has a non-finite position or incoming direction"
            )));
        }
        let params = StochasticParams::new(delta, vpl.xi)?;
        let local = LocalBound::new(vpl, &params, GlossyBound::Ellipsoid)?;
        let (center, axis, along, across) = match local {
            _ if reflects_nothing(vpl) => return Ok(None),
            LocalBound::Empty => return Ok(None),
            LocalBound::Sphere { center, radius_sq } => {
                let r = radius_sq.sqrt();
                (center, DVec3::X, r, r)
            }
            LocalBound::Spheroid {
                center,
                rotation,
                semi_axes,
            } => (
                center,
                rotation.x_axis.as_dvec3().normalize(),
                f64::from(semi_axes.x),
                f64::from(semi_axes.y.max(semi_axes.z)),
            ),
        };
        let relative = vpl.position - self.eye;
        let bound = Bound {
            center: (relative.as_dvec3() + center).as_vec3().to_array(),
            axis: axis.as_vec3().to_array(),
            along: along as f32,
            across: across as f32,
            size: (f64::from(relative.length()) + center.length() + along) as f32,
        };
        let test = || {
            PixelTest::new(
                vpl.position.as_dvec3(),
                vpl.normal.as_dvec3(),
                center,
                axis,
                along,
                across,
            )
        };
        Ok(self.place(vpl, index, &footprint(&bound, &self.map), test))
    }

    /// VPL `index` with its `test` (formed only then) where its `footprint` covers pixels of
    /// its subregion's image (the lanes place theirs eight at a time, `scatter_lanes`).
    fn place(
        &self,
        vpl: &Vpl,
        index: u32,
        footprint: &Footprint<f32>,
        test: impl FnOnce() -> PixelTest,
    ) -> Option<Scattered> {
        if footprint.nowhere {
            return None;
        }
        let subregion = self.subregions.of_vpl(vpl.id);
        let size = self.subregions.size(subregion);
        let pixels = if footprint.everywhere {
            whole(size)
        } else {
            self.subregion_pixels([footprint.lo, footprint.hi], subregion, size)
        }?;
        Some(Scattered {
            index,
            subregion,
            test: test(),
            pixels,
        })
    }

    /// The pixels `[i0, j0, i1, j1]` (inclusive) of subregion `[sx, sy]`'s image (of size
    /// `[sw, sh]`) whose samples may project into the footprint's rectangle; `None` if none.
    ///
    /// Pixel x covers the screen's `[x, x + 1]` and its sample lies at most `stray` outside
    /// it (a negative stray: at least −`stray` inside its edges; −0.5: at its centre), so a
    /// sample at screen position X in `[X0, X1]` has x in `[⌈X0 − stray − 1⌉, ⌊X1 +
    /// stray⌋]`; subregion pixel i is screen pixel sx + K i, and
    /// ⌈(⌈X⌉ − s)/K⌉ = ⌈(X − s)/K⌉ for integers s and K (the same for the floor).
    #[inline(always)]
    pub(crate) fn subregion_pixels(
        &self,
        [lo, hi]: [[f32; 2]; 2],
        [sx, sy]: [u32; 2],
        [sw, sh]: [u32; 2],
    ) -> Option<[u32; 4]> {
        // Both axes formed, then one branch: whether a rectangle is empty is not predictable.
        let subregions = &self.subregions;
        let axis = |a: f32, b: f32, s: u32, n: u32| -> [i64; 2] {
            let s = f64::from(s);
            [
                first_index(subregions.per_k(f64::from(a) - self.stray - 1.0 - s), n),
                last_index(subregions.per_k(f64::from(b) + self.stray - s), n),
            ]
        };
        let [i0, i1] = axis(lo[0], hi[0], sx, sw);
        let [j0, j1] = axis(lo[1], hi[1], sy, sh);
        ((i0 <= i1) & (j0 <= j1)).then_some([i0 as u32, j0 as u32, i1 as u32, j1 as u32])
    }
}

/// Every pixel of a subregion image of size `[sw, sh]`, the rectangle of a footprint that
/// reaches the eye's plane; `None` for an empty image.
#[inline]
pub(crate) fn whole([sw, sh]: [u32; 2]) -> Option<[u32; 4]> {
    (sw > 0 && sh > 0).then(|| [0, 0, sw - 1, sh - 1])
}

/// ⌈x⌉ clamped to `[0, n]` (NaN: 0), without a call into libm or a branch: `f64::clamp`
/// keeps a NaN, which `as` casts to 0.
#[inline(always)]
fn first_index(x: f64, n: u32) -> i64 {
    let x = x.clamp(0.0, f64::from(n));
    let t = x as i64;
    t + i64::from((t as f64) < x)
}

/// ⌊x⌋ clamped to `[-1, n - 1]` (NaN: n − 1), without a call into libm.
#[inline(always)]
fn last_index(x: f64, n: u32) -> i64 {
    let last = f64::from(n) - 1.0;
    let x = if x.is_nan() {
        last
    } else {
        x.clamp(-1.0, last)
    };
    let t = x as i64;
    t - i64::from((t as f64) > x)
}
