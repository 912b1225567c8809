//! The bound each VPL is culled with, computed once per cull in the culling view space:
//! the section-6 sphere for diffuse VPLs, and for glossy VPLs the sphere r/α around q, the
//! sphere r_u around c (section 7) or the GGX spheroid (eq. 12-15) as its stretched and
//! rotated test space BS, BS·c (eq. 16-17, section 5.2).
use crate::bound_lanes::{EllipsoidLanes, SphereLanes};
use crate::partition::Partition;
use crate::view::CullView;
use crate::vpl_lanes::{own_bounds, LaneBound};
use glam::{DMat3, DVec3, Mat3, Vec3};
use rayon::prelude::*;
use slc_bounds::lanes::{load_all, splat_all, store_all, Lanes8, F8};
use slc_bounds::test_space::lanes::{mat3_mul, test_matrices};
use slc_bounds::{BoxBound, GlossyLobe, Sphere, Spheroid, StochasticParams, TestSpace};
pub use slc_core::GlossyBound;
use slc_core::{CullError, Vpl, VplLobe};

/// Relative growth of every bound: radii and semi-axes times 1 + 1e-3. slc-bounds computes
/// the bounds exactly in f64 but stores them, and their rotations, in f32; the view rotation is
/// f32 too, and one ulp (6e-8) of rotation tilts the needle-like spheroid of α = 1e-3
/// (r_u = 500 r, eq. 13) by 3e-5 of its thin radius at its far end. The shader (and the truth
/// in `metrics`) evaluates p(ωo, l) of eq. (2) in f32 as well. Without growth the tests find
/// contributing pairs outside the bounds (still some at 2e-5, none at 1e-4); 1e-3 keeps a
/// factor of 10 of margin for about 0.3% more volume.
pub const BOUND_SLACK: f64 = 1e-3;

/// A sphere in view space: centre, squared radius, and the VPL's index in the input.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ViewSphere {
    pub center: DVec3,
    pub radius_sq: f64,
    pub index: u32,
}

/// An ellipsoid's test space (section 5.2): the columns of BS (BS e_x, BS e_y, BS e_z) and
/// the transformed centre BS·c, for the view-space ellipsoid; inside it the ellipsoid is the
/// unit ball around BS·c.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ViewEllipsoid {
    pub columns: [DVec3; 3],
    pub center: DVec3,
    pub index: u32,
}

/// One VPL's bound. `Empty` (zero flux, ωi·n <= 0, kd = 0 for a diffuse VPL) is never listed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum VplBound {
    Empty,
    Sphere(ViewSphere),
    Ellipsoid(ViewEllipsoid),
}

/// A VPL's own bound around its position q (q at the origin, world axes), grown by
/// [`BOUND_SLACK`]: the section-6 sphere of a diffuse VPL, and for a glossy VPL the sphere
/// r/α, the sphere r_u around c (section 7) or the GGX spheroid of eq. (12)-(15). `Empty`
/// (zero flux, ωi·n <= 0, kd = 0 for a diffuse VPL) contains nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum LocalBound {
    Empty,
    Sphere {
        center: DVec3,
        radius_sq: f64,
    },
    Spheroid {
        center: DVec3,
        rotation: Mat3,
        semi_axes: Vec3,
    },
}

impl LocalBound {
    /// The bound of `vpl` for the roulette `params` (eq. 2-3). The slc-bounds constructors
    /// build it around the origin, so its offset from q is as precise as the bound itself,
    /// whatever the world coordinates.
    pub(crate) fn new(
        vpl: &Vpl,
        params: &StochasticParams,
        glossy: GlossyBound,
    ) -> Result<Self, CullError> {
        match vpl.lobe {
            VplLobe::Diffuse => {
                // The diffuse BRDF is one-sided: nothing is reflected for ωi below the surface.
                if vpl.normal.dot(vpl.omega_i) <= 0.0 {
                    return Ok(Self::Empty);
                }
                Ok(Self::sphere(Sphere::diffuse(&vpl.diffuse_lobe()?, params)?))
            }
            VplLobe::Glossy => Self::glossy(&vpl.glossy_lobe()?, params, glossy),
        }
    }

    /// [`Self::new`] for a glossy VPL's lobe (validated by slc-bounds).
    pub(crate) fn glossy(
        lobe: &GlossyLobe,
        params: &StochasticParams,
        glossy: GlossyBound,
    ) -> Result<Self, CullError> {
        Ok(match glossy {
            GlossyBound::Sphere => Self::sphere(Sphere::around_vpl(lobe, params)?),
            GlossyBound::EnclosingSphere => {
                Self::sphere(Sphere::enclosing(&Spheroid::new(lobe, params)?))
            }
            GlossyBound::Ellipsoid | GlossyBound::Tight => {
                Self::spheroid(&Spheroid::new(lobe, params)?)
            }
        })
    }

    fn sphere(sphere: Sphere) -> Self {
        if sphere.is_empty() {
            return Self::Empty;
        }
        let radius = f64::from(sphere.radius) * (1.0 + BOUND_SLACK);
        Self::Sphere {
            center: sphere.center.as_dvec3(),
            radius_sq: radius * radius,
        }
    }

    fn spheroid(spheroid: &Spheroid) -> Self {
        if spheroid.is_empty() {
            return Self::Empty;
        }
        Self::Spheroid {
            center: spheroid.center().as_dvec3(),
            rotation: spheroid.rotation(),
            semi_axes: (spheroid.semi_axes().as_dvec3() * (1.0 + BOUND_SLACK)).as_vec3(),
        }
    }
}

/// The bound of p over boxes of receivers (`slc_bounds::BoxBound`) of `vpl`'s lobe, in
/// world axes with q at the origin. A diffuse VPL with ωi below its surface reflects nothing
/// (its culling bound is empty, so it is never refined).
pub(crate) fn lobe_box_bound(vpl: &Vpl, params: &StochasticParams) -> Result<BoxBound, CullError> {
    Ok(match vpl.lobe {
        VplLobe::Diffuse => BoxBound::diffuse(&vpl.diffuse_lobe()?, params),
        VplLobe::Glossy => BoxBound::glossy(&vpl.glossy_lobe()?, params),
    })
}

impl VplBound {
    /// The bound of VPL `index` for δ = `delta` (eq. 2) in the culling view: the
    /// [`LocalBound`] moved to the VPL in f64 (`R (q − eye + local centre)`), so its position
    /// is as precise as the G-buffer samples'.
    pub(crate) fn new(
        vpl: &Vpl,
        index: u32,
        delta: f32,
        view: &CullView,
        glossy: GlossyBound,
    ) -> Result<Self, CullError> {
        if !(vpl.position.is_finite() && vpl.omega_i.is_finite()) {
            return Err(CullError::Input(format!(
                "VPL {index} has a non-finite position or incoming direction"
            )));
        }
        let params = StochasticParams::new(delta, vpl.xi)?;
        let q = view.relative(vpl.position);
        match LocalBound::new(vpl, &params, glossy)? {
            LocalBound::Empty => Ok(Self::Empty),
            LocalBound::Sphere { center, radius_sq } => Ok(Self::Sphere(ViewSphere {
                center: view.rotate(q + center),
                radius_sq,
                index,
            })),
            LocalBound::Spheroid {
                center,
                rotation,
                semi_axes,
            } => Self::ellipsoid(view, q + center, rotation, semi_axes, index),
        }
    }

    /// The bounds of `vpls` (one to eight, VPL k numbered `first + k`) into `out`, as
    /// [`Self::new`] forms them, with the own bounds of the plain VPLs from the lanes
    /// ([`crate::vpl_lanes`]) where `glossy` is the spheroid of eq. (12)-(15) (a diffuse
    /// VPL's sphere is the same for every `glossy`), and those spheroids' test spaces formed
    /// eight at a time too (the same as one at a time, bit for bit). Errors as [`Self::new`],
    /// for the first VPL it refuses.
    pub(crate) fn eight(
        vpls: &[Vpl],
        first: u32,
        delta: f32,
        view: &CullView,
        glossy: GlossyBound,
        out: &mut [Self],
    ) -> Result<(), CullError> {
        let last = vpls.len() - 1;
        let group: [&Vpl; 8] = core::array::from_fn(|k| &vpls[k.min(last)]);
        let (formed, bounds) = own_bounds(&group[..=last], |k| (delta, group[k].xi));
        let spheroid = matches!(glossy, GlossyBound::Ellipsoid | GlossyBound::Tight);
        let own: [Option<LaneBound>; 8] = core::array::from_fn(|k| {
            let lanes = k <= last
                && formed >> k & 1 == 1
                && (spheroid || group[k].lobe == VplLobe::Diffuse);
            lanes.then(|| bounds.lane(k))
        });
        // The glossy ones' test spaces eight at a time.
        let spheroids: [Option<(Mat3, Vec3)>; 8] = core::array::from_fn(|k| match own[k] {
            Some(b) if group[k].lobe == VplLobe::Glossy => Some(spheroid_axes(&b)),
            _ => None,
        });
        let (spaces, matrices) = test_spaces(&spheroids, view.rotation());
        for (k, (vpl, out)) in vpls.iter().zip(out).enumerate() {
            let index = first + k as u32;
            *out = match (own[k], spaces >> k & 1 == 1) {
                (Some(b), true) => {
                    let bs = lane_matrix(&matrices, k);
                    let center = view.relative(vpl.position) + b.offset;
                    Self::from_test_space(view, center, bs, index)
                }
                (Some(b), false) => Self::of_lane(&b, vpl, index, view)?,
                (None, _) => Self::new(vpl, index, delta, view, glossy)?,
            };
        }
        Ok(())
    }

    /// The bound of VPL `index` whose own bound the lanes formed (`b`).
    fn of_lane(b: &LaneBound, vpl: &Vpl, index: u32, view: &CullView) -> Result<Self, CullError> {
        let center = view.relative(vpl.position) + b.offset;
        match vpl.lobe {
            VplLobe::Diffuse => Ok(Self::Sphere(ViewSphere {
                center: view.rotate(center),
                radius_sq: b.along * b.along,
                index,
            })),
            VplLobe::Glossy => {
                let (rotation, semi_axes) = spheroid_axes(b);
                Self::ellipsoid(view, center, rotation, semi_axes, index)
            }
        }
    }

    /// The test space of eq. (16)-(17) of a spheroid with world rotation `rotation`,
    /// camera-relative centre `center` and `semi_axes`. BS comes from [`TestSpace::new`]
    /// (with the view rotation applied to R, section 5.1); BS·c is formed here in f64.
    fn ellipsoid(
        view: &CullView,
        center: DVec3,
        rotation: Mat3,
        semi_axes: Vec3,
        index: u32,
    ) -> Result<Self, CullError> {
        // The centre passed here only feeds TestSpace's own f32 BS·c, which is not used.
        let bs = TestSpace::new(view.rotation() * rotation, semi_axes, Vec3::ZERO)?.matrix();
        Ok(Self::from_test_space(view, center, bs, index))
    }

    /// The ellipsoid of test space `bs` (BS of eq. 16-17) centred `center` (camera-relative),
    /// with BS·c formed in f64.
    fn from_test_space(view: &CullView, center: DVec3, bs: Mat3, index: u32) -> Self {
        let bs = bs.as_dmat3();
        Self::Ellipsoid(ViewEllipsoid {
            columns: [bs.x_axis, bs.y_axis, bs.z_axis],
            center: bs * view.rotate(center),
            index,
        })
    }
}

/// The world rotation [ω_u t1 t2] (any unit t1, t2 across the axis, in f64) and the semi-axes
/// of a spheroid the lanes formed, in f32 as the test space takes them.
fn spheroid_axes(b: &LaneBound) -> (Mat3, Vec3) {
    let (t1, t2) = b.axis.any_orthonormal_pair();
    (
        DMat3::from_cols(b.axis, t1, t2).as_mat3(),
        DVec3::new(b.along, b.across, b.across).as_vec3(),
    )
}

/// BS of `TestSpace::new(view_rotation * R, semi_axes, 0)` for each spheroid (R, semi-axes)
/// of `spheroids`, eight at a time (`slc_bounds::test_space::lanes`: the same matrix bit for
/// bit), as columns of lanes; and the spheroids it formed one for (bit k). The others are
/// the caller's to form one at a time, or to refuse.
fn test_spaces(spheroids: &[Option<(Mat3, Vec3)>; 8], view_rotation: Mat3) -> (u8, [[F8; 3]; 3]) {
    let wanted = (0..8).fold(0u8, |bits, k| bits | u8::from(spheroids[k].is_some()) << k);
    if wanted == 0 {
        return (0, [[F8([0.0; 8]); 3]; 3]);
    }
    // A lane without a spheroid takes the identity, which the lanes accept (and drop below).
    let (mut rotation, mut semi) = ([[F8([0.0; 8]); 3]; 3], [F8([1.0; 8]); 3]);
    for (k, s) in spheroids.iter().enumerate() {
        let (r, axes) = s.unwrap_or((Mat3::IDENTITY, Vec3::ONE));
        for (j, column) in r.to_cols_array_2d().into_iter().enumerate() {
            for (i, v) in column.into_iter().enumerate() {
                rotation[j][i].0[k] = v;
            }
        }
        for (i, v) in axes.to_array().into_iter().enumerate() {
            semi[i].0[k] = v;
        }
    }
    let view = view_rotation.to_cols_array_2d();
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        let (formed, matrices) = unsafe { test_spaces_avx2(&rotation, &semi, &view) };
        return (formed & wanted, matrices);
    }
    let (formed, matrices) = test_spaces_in::<F8>(&rotation, &semi, &view);
    (formed & wanted, matrices)
}

/// Lane `k` of a matrix whose columns are lanes (as [`test_spaces`] returns them).
fn lane_matrix(columns: &[[F8; 3]; 3], k: usize) -> Mat3 {
    Mat3::from_cols_array_2d(&columns.map(|c| c.map(|v| v.0[k])))
}

/// [`test_spaces_in`] in AVX registers.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn test_spaces_avx2(
    rotation: &[[F8; 3]; 3],
    semi: &[F8; 3],
    view: &[[f32; 3]; 3],
) -> (u8, [[F8; 3]; 3]) {
    test_spaces_in::<slc_bounds::lanes_avx::A8>(rotation, semi, view)
}

/// [`test_spaces`] in lanes of `L`: the view rotation times each R as glam multiplies
/// them, then BS.
#[inline(always)]
fn test_spaces_in<L: Lanes8>(
    rotation: &[[F8; 3]; 3],
    semi: &[F8; 3],
    view: &[[f32; 3]; 3],
) -> (u8, [[F8; 3]; 3]) {
    let rotation = [
        load_all::<L, 3>(&rotation[0]),
        load_all(&rotation[1]),
        load_all(&rotation[2]),
    ];
    let view = [
        splat_all::<L, 3>(&view[0]),
        splat_all(&view[1]),
        splat_all(&view[2]),
    ];
    let (matrix, ok) = test_matrices(mat3_mul(view, rotation), load_all(semi));
    (
        L::bits(ok),
        [
            store_all(&matrix[0]),
            store_all(&matrix[1]),
            store_all(&matrix[2]),
        ],
    )
}

/// The non-empty bounds of one subregion's VPLs, spheres and ellipsoids apart (each ascending
/// in the VPL index), so the culling loops run without a branch on the kind.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct SubregionBounds {
    pub spheres: Vec<ViewSphere>,
    pub ellipsoids: Vec<ViewEllipsoid>,
    /// The same bounds in f32 lanes, for the tiles' pre-test.
    pub sphere_lanes: SphereLanes,
    pub ellipsoid_lanes: EllipsoidLanes,
}

/// Every VPL's bound (in parallel, into `every`), grouped by interleaved subregion into
/// `out`: both written in their memory (a previous frame's), their old entries dropped.
pub(crate) fn subregion_bounds(
    vpls: &[Vpl],
    partition: &Partition,
    delta: f32,
    view: &CullView,
    glossy: GlossyBound,
    every: &mut Vec<VplBound>,
    out: &mut Vec<SubregionBounds>,
) -> Result<(), CullError> {
    // Eight VPLs at a time (their own bounds share lanes), in `every`'s memory.
    every.resize(vpls.len(), VplBound::Empty);
    every
        .par_chunks_mut(8)
        .zip(vpls.par_chunks(8))
        .enumerate()
        .try_for_each(|(c, (out, eight))| {
            VplBound::eight(eight, 8 * c as u32, delta, view, glossy, out)
        })?;
    out.resize_with(partition.subregions(), SubregionBounds::default);
    out.par_iter_mut().enumerate().for_each(|(s, out)| {
        out.spheres.clear();
        out.ellipsoids.clear();
        for &i in partition.of(s as u32) {
            match every[i as usize] {
                VplBound::Empty => {}
                VplBound::Sphere(b) => out.spheres.push(b),
                VplBound::Ellipsoid(b) => out.ellipsoids.push(b),
            }
        }
        out.sphere_lanes.refill(&out.spheres);
        out.ellipsoid_lanes.refill(&out.ellipsoids);
    });
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use slc_bounds::{Brdf, Fresnel, GlossyLobe};
    use slc_core::Camera;

    fn view() -> CullView {
        let cam = Camera::look_at(
            Vec3::new(100.0, 1.0, 3.0),
            Vec3::new(100.0, 1.0, 0.0),
            Vec3::Y,
            1.0,
        )
        .unwrap();
        CullView::new(&cam, 32, 32).unwrap()
    }

    fn vpl(lobe: VplLobe, omega_i: Vec3, flux: Vec3, alpha: f32) -> Vpl {
        Vpl {
            position: Vec3::new(100.2, 0.5, -0.3),
            normal: Vec3::Z,
            geometric_normal: Vec3::Z,
            omega_i,
            flux,
            brdf: Brdf {
                kd: Vec3::splat(0.5),
                fresnel: Fresnel::Schlick(Vec3::splat(0.9)),
                alpha,
                anisotropy: None,
            },
            lobe,
            id: 0,
            xi: 0.3,
        }
    }

    /// `VplBound::eight` forms the bounds `VplBound::new` forms, the plain VPLs' from the lanes:
    /// over random VPLs of both lobes (δ from 1e-9 to 1e3, one in twenty subnormal, 0 or NaN; flux
    /// from 1e-6 to 1e6, and 1e-24 times that at one VPL in ten and wherever δ is out of the
    /// domain, where a subnormal δ gives the lanes a finite range; α from 0.01 to 1; ξ near 0 and
    /// 1; one in ten spoilt by a NaN position, a ξ of 0 or an α of 0.001) in groups of one to
    /// eight, the same kind of bound or the same error for the first VPL refused; and `eight`'s
    /// sphere or ellipsoid holds every point of `new`'s shrunk by 2e-5, for every `GlossyBound` (a
    /// shortfall of 4e-5 fails). (Not every point of `new`'s own surface: each test space rounds BS
    /// to f32, a few ε per entry, which the spheroid's elongation (1 + α²)/(2α), up to 50, raises
    /// to about 1e-5 of the unit ball, as large as the lanes' own growth; `BOUND_SLACK`, 1e-3,
    /// covers both.)
    #[test]
    fn eight_at_a_time_contain_the_bounds_one_at_a_time() {
        use crate::test_rng::{random_vpl, Rng};
        let view = view();
        let mut rng = Rng(0xE16_B0D5);
        let (mut compared, mut points, mut lanes, mut from_lanes) = (0, 0, 0, 0);
        for case in 0..1500 {
            // One δ in twenty outside slc-bounds' domain (subnormal, 0, NaN).
            let delta = match case % 20 {
                0 => [1e-39, 0.0, f32::NAN][case as usize / 20 % 3],
                _ => 10f32.powf(rng.range(-9.0, 3.0)),
            };
            let glossy = [
                GlossyBound::Sphere,
                GlossyBound::EnclosingSphere,
                GlossyBound::Ellipsoid,
                GlossyBound::Tight,
            ][case as usize % 4];
            let count = 1 + case as usize % 8;
            let vpls: Vec<Vpl> = (0..count)
                .map(|k| {
                    let mut v = random_vpl(&mut rng, case * 8 + k as u32);
                    v.position += Vec3::new(100.0, 1.0, -3.0);
                    match (rng.f32() * 30.0) as u32 {
                        0 => v.position.y = f32::NAN,
                        1 => v.xi = 0.0,
                        2 => v.brdf.alpha = 1e-3,
                        _ => {}
                    }
                    // A flux whose range a subnormal δ makes finite, with every such δ and at
                    // one VPL in ten otherwise.
                    if case % 20 == 0 || rng.f32() < 0.1 {
                        v.flux *= 1e-24;
                    }
                    v
                })
                .collect();
            let one: Vec<_> = (0..count)
                .map(|k| VplBound::new(&vpls[k], 40 + k as u32, delta, &view, glossy))
                .collect();
            let mut out = vec![VplBound::Empty; count];
            let eight = VplBound::eight(&vpls, 40, delta, &view, glossy, &mut out);
            if let Some(Err(first)) = one.iter().find(|b| b.is_err()) {
                let got = eight.expect_err("a VPL is refused");
                assert_eq!(got.to_string(), first.to_string(), "case {case}");
                continue;
            }
            eight.unwrap();
            // Where the lanes formed a VPL's own bound, its bound is the one `of_lane` forms
            // one VPL at a time, bit for bit (the test spaces eight at a time included).
            let refs: Vec<&Vpl> = vpls.iter().collect();
            let (formed, bounds) = own_bounds(&refs, |k| (delta, vpls[k].xi));
            let spheroid = matches!(glossy, GlossyBound::Ellipsoid | GlossyBound::Tight);
            for (k, vpl) in vpls.iter().enumerate() {
                if formed >> k & 1 == 1 && (spheroid || vpl.lobe == VplLobe::Diffuse) {
                    let lane = VplBound::of_lane(&bounds.lane(k), vpl, 40 + k as u32, &view);
                    let (lane, got) = (format!("{:?}", lane.unwrap()), format!("{:?}", out[k]));
                    assert_eq!(lane, got, "case {case}, VPL {k}: one at a time");
                    lanes += 1;
                }
            }
            // The glossy ones' test spaces came from the lanes (most of them: the lanes
            // refuse none that `TestSpace::new` accepts here).
            let spheroids: [Option<(Mat3, Vec3)>; 8] = core::array::from_fn(|k| {
                let glossy = k < count && vpls[k].lobe == VplLobe::Glossy;
                (spheroid && glossy && formed >> k & 1 == 1).then(|| spheroid_axes(&bounds.lane(k)))
            });
            let (spaces, matrices) = test_spaces(&spheroids, view.rotation());
            for (k, s) in spheroids.iter().enumerate() {
                if let Some((rotation, semi)) = s {
                    assert_eq!(spaces >> k & 1, 1, "case {case}, VPL {k}: left");
                    let one = TestSpace::new(view.rotation() * *rotation, *semi, Vec3::ZERO);
                    let lane = lane_matrix(&matrices, k);
                    assert_eq!(format!("{lane:?}"), format!("{:?}", one.unwrap().matrix()));
                    from_lanes += 1;
                }
            }
            for (k, (want, got)) in one.iter().zip(&out).enumerate() {
                compared += 1;
                let unit = |rng: &mut Rng| loop {
                    let u = DVec3::new(
                        rng.range64(-1.0, 1.0),
                        rng.range64(-1.0, 1.0),
                        rng.range64(-1.0, 1.0),
                    );
                    if let Some(u) = u.try_normalize() {
                        break u * (1.0 - 2e-5);
                    }
                };
                // Bounds smaller than a millionth of their distance from the eye are compared
                // by kind only: f64 cannot place 2e-5 of them.
                match (want.as_ref().unwrap(), got) {
                    (VplBound::Empty, VplBound::Empty) => {}
                    (VplBound::Sphere(a), VplBound::Sphere(_))
                        if a.center.length() > 1e6 * a.radius_sq.sqrt() => {}
                    (VplBound::Ellipsoid(a), VplBound::Ellipsoid(_)) if a.center.length() > 1e6 => {
                    }
                    (VplBound::Sphere(a), VplBound::Sphere(b)) => {
                        for _ in 0..20 {
                            let x = a.center + unit(&mut rng) * a.radius_sq.sqrt();
                            points += 1;
                            let d_sq = (x - b.center).length_squared();
                            assert!(d_sq <= b.radius_sq, "case {case}, VPL {k}");
                        }
                    }
                    (VplBound::Ellipsoid(a), VplBound::Ellipsoid(b)) => {
                        let [bs_a, bs_b] = [a, b].map(|e| {
                            let [x, y, z] = e.columns;
                            DMat3::from_cols(x, y, z)
                        });
                        let inverse = bs_a.inverse();
                        for _ in 0..20 {
                            let x = inverse * (unit(&mut rng) + a.center);
                            points += 1;
                            let u = bs_b * x - b.center;
                            assert!(u.length_squared() <= 1.0, "case {case}, VPL {k}: {u}");
                        }
                    }
                    (a, b) => panic!("case {case}, VPL {k}: {a:?} one at a time, {b:?} eight"),
                }
            }
        }
        assert!(
            compared > 4000 && points > 40_000 && lanes > 2000 && from_lanes > 1000,
            "{compared} compared, {points} points, {lanes} own bounds and {from_lanes} test \
             spaces from the lanes"
        );
    }

    #[test]
    fn nothing_reflected_gives_an_empty_bound() {
        let v = view();
        let below = Vec3::new(0.6, 0.0, -0.8);
        for glossy in [
            GlossyBound::Sphere,
            GlossyBound::EnclosingSphere,
            GlossyBound::Ellipsoid,
        ] {
            for lobe in [VplLobe::Diffuse, VplLobe::Glossy] {
                let dark = vpl(lobe, Vec3::Z, Vec3::ZERO, 0.2);
                assert_eq!(
                    VplBound::new(&dark, 0, 1e-3, &v, glossy).unwrap(),
                    VplBound::Empty
                );
                let back = vpl(lobe, below, Vec3::ONE, 0.2);
                assert_eq!(
                    VplBound::new(&back, 0, 1e-3, &v, glossy).unwrap(),
                    VplBound::Empty
                );
            }
        }
    }

    /// The view-space bounds agree with the world-space ones of slc-bounds: points of the
    /// spheroid are inside the test space's unit ball, points of the spheres inside them.
    #[test]
    fn view_space_bounds_match_world_bounds() {
        let v = view();
        let wi = Vec3::new(0.3, 0.4, 0.866).normalize();
        let g = vpl(VplLobe::Glossy, wi, Vec3::splat(3.0), 0.05);
        let params = StochasticParams::new(1e-3, g.xi).unwrap();
        let lobe = GlossyLobe::new(g.position, g.normal, wi, 0.05, g.flux, g.brdf.fresnel).unwrap();
        let spheroid = Spheroid::new(&lobe, &params).unwrap();
        let VplBound::Ellipsoid(e) =
            VplBound::new(&g, 0, 1e-3, &v, GlossyBound::Ellipsoid).unwrap()
        else {
            panic!("ellipsoid expected")
        };
        let bs = glam::DMat3::from_cols(e.columns[0], e.columns[1], e.columns[2]);
        for k in 0..200 {
            let t = k as f32 * 0.7;
            let dir = Vec3::new(
                t.sin() * (t * 0.3).cos(),
                t.cos(),
                t.sin() * (t * 0.3).sin(),
            );
            let p =
                spheroid.center() + spheroid.rotation() * (spheroid.semi_axes() * dir.normalize());
            let d = (bs * v.to_view(p) - e.center).length();
            assert!(d <= 1.0 && d > 0.99, "{d}");
        }
        let VplBound::Sphere(s) = VplBound::new(&g, 0, 1e-3, &v, GlossyBound::Sphere).unwrap()
        else {
            panic!("sphere expected")
        };
        let r = f64::from(Sphere::around_vpl(&lobe, &params).unwrap().radius);
        assert!((s.center - v.to_view(g.position)).length() < 1e-9);
        assert!((s.radius_sq.sqrt() / r - 1.0 - BOUND_SLACK).abs() < 1e-6);
    }

    #[test]
    fn invalid_vpls_are_errors() {
        let v = view();
        let mut bad = vpl(VplLobe::Glossy, Vec3::Z, Vec3::ONE, 0.2);
        bad.xi = 0.0;
        assert!(VplBound::new(&bad, 0, 1e-3, &v, GlossyBound::Ellipsoid).is_err());
        let mut nan = vpl(VplLobe::Diffuse, Vec3::Z, Vec3::ONE, 0.2);
        nan.position.x = f32::NAN;
        assert!(VplBound::new(&nan, 0, 1e-3, &v, GlossyBound::Ellipsoid).is_err());
        let rough = vpl(VplLobe::Glossy, Vec3::Z, Vec3::ONE, 0.0);
        assert!(VplBound::new(&rough, 0, 1e-3, &v, GlossyBound::Ellipsoid).is_err());
        let ok = vpl(VplLobe::Glossy, Vec3::Z, Vec3::ONE, 0.2);
        assert!(VplBound::new(&ok, 0, 0.0, &v, GlossyBound::Sphere).is_err());
    }
}
