//! The deterministic generator of the unit tests (xorshift64*), and random VPLs from it.
use crate::scatter::PixelTest;
use crate::vpl_bounds::LocalBound;
use glam::{DMat3, DVec3, Vec3};
use slc_bounds::{Brdf, Fresnel};
use slc_core::{Vpl, VplLobe};

pub(crate) struct Rng(pub u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// Uniform in [0, 1), 24 bits.
    pub(crate) fn f32(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Uniform in [0, 1), 53 bits.
    pub(crate) fn f64(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    pub(crate) fn range(&mut self, a: f32, b: f32) -> f32 {
        a + (b - a) * self.f32()
    }

    pub(crate) fn range64(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.f64()
    }
}

/// A random VPL of either lobe: unit vectors, ωi mostly above the surface, flux from 1e-6 to
/// 1e6, α from 0.01 to 1, ξ near 0 or 1 one time in five.
pub(crate) fn random_vpl(rng: &mut Rng, id: u32) -> Vpl {
    let unit = |rng: &mut Rng| loop {
        let v = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        if v.length_squared() > 1e-3 && v.length_squared() <= 1.0 {
            break v.normalize();
        }
    };
    let normal = unit(rng);
    let mut omega_i = unit(rng);
    if omega_i.dot(normal) < 0.0 && rng.f32() < 0.9 {
        omega_i = -omega_i;
    }
    Vpl {
        position: Vec3::new(
            rng.range(-5.0, 5.0),
            rng.range(-5.0, 5.0),
            rng.range(-20.0, 2.0),
        ),
        normal,
        geometric_normal: normal,
        omega_i,
        flux: Vec3::new(rng.f32(), rng.f32(), rng.f32()) * 10f32.powf(rng.range(-6.0, 6.0)),
        brdf: Brdf {
            kd: Vec3::new(rng.f32(), rng.f32(), rng.f32()),
            fresnel: Fresnel::Schlick(Vec3::new(rng.f32(), rng.f32(), rng.f32())),
            alpha: 10f32.powf(rng.range(-2.0, 0.0)),
            anisotropy: None,
        },
        lobe: if rng.f32() < 0.7 {
            VplLobe::Glossy
        } else {
            VplLobe::Diffuse
        },
        id,
        xi: if rng.f32() < 0.2 {
            [1e-6, 1.0 - 1e-6][rng.f32().round() as usize]
        } else {
            rng.range(1e-4, 1.0)
        },
    }
}

/// A random point of a non-empty `bound` relative to q: its centre plus a random direction's
/// point of its surface times a scale drawn from `scale`.
pub(crate) fn point_of(bound: &LocalBound, rng: &mut Rng, scale: [f64; 2]) -> DVec3 {
    let (center, rotation, semi) = match *bound {
        LocalBound::Sphere { center, radius_sq } => {
            (center, DMat3::IDENTITY, DVec3::splat(radius_sq.sqrt()))
        }
        LocalBound::Spheroid {
            center,
            rotation,
            semi_axes,
        } => (center, rotation.as_dmat3(), semi_axes.as_dvec3()),
        LocalBound::Empty => panic!("an empty bound has no points"),
    };
    let u = loop {
        let u = DVec3::new(
            rng.range64(-1.0, 1.0),
            rng.range64(-1.0, 1.0),
            rng.range64(-1.0, 1.0),
        );
        if let Some(u) = u.try_normalize() {
            break u;
        }
    };
    center + rotation * (semi * u * rng.range64(scale[0], scale[1]))
}

/// A random unit vector.
pub(crate) fn unit(rng: &mut Rng) -> DVec3 {
    loop {
        let v = DVec3::new(
            rng.range64(-1.0, 1.0),
            rng.range64(-1.0, 1.0),
            rng.range64(-1.0, 1.0),
        );
        if (0.01..=1.0).contains(&v.length_squared()) {
            return v.normalize();
        }
    }
}

/// A random bound: semi-axes from 1e-6 to 1e6 with eccentricities up to 10^`ecc` (either
/// way), the VPL up to 10^`far` times the larger semi-axis from the origin and the centre
/// off the VPL; the normal zero so that only the bound decides.
pub(crate) fn bound(rng: &mut Rng, ecc: f64, far: f64) -> PixelTest {
    let along = 10f64.powf(rng.range64(-6.0, 6.0));
    let across = along * 10f64.powf(rng.range64(-ecc, ecc));
    let axis = unit(rng);
    let position = (unit(rng) * along.max(across) * 10f64.powf(rng.range64(-1.0, far)))
        .as_vec3()
        .as_dvec3();
    let center = axis * along * rng.range64(-1.5, 1.5);
    PixelTest::new(position, DVec3::ZERO, center, axis, along, across)
}

/// The f32 point `w` of the unit ball maps to in `test`'s bound.
pub(crate) fn point(test: &PixelTest, w: DVec3) -> Vec3 {
    let [along, across] = test.semi_axes();
    let any = if test.axis.x.abs() < 0.9 {
        DVec3::X
    } else {
        DVec3::Y
    };
    let b1 = test.axis.cross(any).normalize();
    let b2 = test.axis.cross(b1);
    let e = test.axis * (w.x * along) + (b1 * w.y + b2 * w.z) * across;
    (test.position + test.center + e).as_vec3()
}

/// The bounds of the lane tests' checks, varied by `round`: [`bound`]s of eccentricities up
/// to 1e5 and VPLs up to 1e4 times their size from the origin; one time in four needles up to
/// 1e8 long for their width with their centres up to 30 lengths off the VPL (slacks beyond
/// the bound's own size); one time in two with a random normal (else none).
pub(crate) fn varied_bound(rng: &mut Rng, round: u32) -> PixelTest {
    let mut test = bound(rng, 5.0, 4.0);
    if round % 4 == 3 {
        let b = bound(rng, 8.0, 4.0);
        let [along, across] = b.semi_axes();
        let center = b.center * rng.range64(1.0, 20.0);
        test = PixelTest::new(b.position, b.normal, center, b.axis, along, across);
    }
    if round % 2 == 1 {
        test.normal = unit(rng).as_vec3().as_dvec3();
    }
    test
}
