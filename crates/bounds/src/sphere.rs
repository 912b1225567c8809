//! Bounding spheres: the diffuse VPL sphere of section 6 and the two glossy baselines of
//! section 7.
use crate::check;
use crate::diffuse::DiffuseLobe;
use crate::error::BoundsError;
use crate::glossy::GlossyLobe;
use crate::spheroid::Spheroid;
use crate::stochastic::StochasticParams;
use glam::Vec3;

/// A closed ball. A radius of 0 (or less) is an empty sphere that contains nothing, which
/// culls its light everywhere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    pub center: Vec3,
    pub radius: f32,
}

impl Sphere {
    /// The bounding sphere of a diffuse VPL (section 6). Its range l_max(ωo) = R sqrt(ωo·n),
    /// R = sqrt(Φk/(π δ ξ)) (eq. 5), traces the surface ρ³ = R² z around q; its smallest
    /// enclosing sphere has radius (4/27)^(1/4) R, as in the paper, and centre
    /// q + (1/27)^(1/4) R n.
    ///
    /// The paper prints the centre as q + (1/3)^(1/4) R n; with that centre the sphere would
    /// not contain q itself (0.76 R > 0.62 R), where p = 1, so it would cull a light at its
    /// own position: (1/27)^(1/4) is the centre that makes the stated radius enclose the range.
    pub fn diffuse(lobe: &DiffuseLobe, params: &StochasticParams) -> Result<Self, BoundsError> {
        let range = lobe.peak_range(params)?;
        let offset = range * (1.0f32 / 27.0).powf(0.25);
        Ok(Self {
            center: check::fits_vec(lobe.position() + offset * lobe.normal(), "sphere centre")?,
            radius: range * (4.0f32 / 27.0).powf(0.25),
        })
    }

    /// The baseline sphere of section 7 after Tokuyoshi and Harada 2016 (TH16): centred at the
    /// VPL q with radius r/α, the maximum of s(ωo) in eq. (12) (from the maximum D(1) =
    /// 1/(π α²) of the NDF).
    pub fn around_vpl(lobe: &GlossyLobe, params: &StochasticParams) -> Result<Self, BoundsError> {
        let r = f64::from(lobe.radius(params)?);
        Ok(Self {
            center: lobe.position(),
            radius: check::fits(r / f64::from(lobe.alpha()), "sphere radius r/alpha")?,
        })
    }

    /// The baseline sphere of section 7 enclosing the spheroid: centre c (eq. 15), radius r_u
    /// (eq. 13). Empty if the spheroid is.
    #[inline]
    pub fn enclosing(spheroid: &Spheroid) -> Self {
        Self {
            center: spheroid.center(),
            radius: spheroid.semi_axes().x,
        }
    }

    /// Whether the sphere is empty (radius <= 0 or NaN), the bound of an r = 0 light (eq. 12).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.radius.is_nan() || self.radius <= 0.0
    }

    /// Whether `point` lies in the closed ball, `|p − c| <= radius` (the bounding test of
    /// sections 6-7). False for an empty sphere; divides before squaring, so no overflow.
    #[inline]
    pub fn contains(&self, point: Vec3) -> bool {
        if self.is_empty() {
            return false;
        }
        let d = (point - self.center) / self.radius;
        d.abs().max_element() <= 1.0 && d.length_squared() <= 1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_util::{fibonacci, Rng};

    fn diffuse_case(rng: &mut Rng) -> (DiffuseLobe, StochasticParams) {
        let q = Vec3::new(
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
        );
        let flux = Vec3::new(
            rng.range(0.0, 50.0),
            rng.range(0.0, 50.0),
            rng.range(0.0, 50.0),
        );
        let kd = Vec3::new(rng.f32(), rng.f32(), rng.f32());
        let lobe = DiffuseLobe::new(q, rng.unit(), flux, kd).unwrap();
        let delta = 10f32.powf(rng.range(-5.0, 1.0));
        let params = StochasticParams::new(delta, rng.range(1e-6, 1.0)).unwrap();
        (lobe, params)
    }

    #[test]
    fn diffuse_sphere_encloses_the_range_and_is_tight() {
        let mut rng = Rng::new(21);
        for _ in 0..100 {
            let (lobe, params) = diffuse_case(&mut rng);
            let sphere = Sphere::diffuse(&lobe, &params).unwrap();
            let (c, radius) = (sphere.center.as_dvec3(), f64::from(sphere.radius));
            assert!(
                sphere.contains(lobe.position()),
                "q itself (p = 1 at l = 0)"
            );
            let mut farthest = 0.0f64;
            for k in 0..3000 {
                let dir = fibonacci(k, 3000);
                let l = f64::from(params.range(lobe.intensity(dir)));
                let p = lobe.position().as_dvec3() + l * dir.as_dvec3();
                farthest = farthest.max((p - c).length() / radius);
            }
            assert!(farthest <= 1.0 + 1e-5, "outside: {farthest}");
            assert!(farthest >= 0.995, "too loose: {farthest}");
        }
    }

    #[test]
    fn empty_sphere_contains_nothing() {
        let lobe = DiffuseLobe::new(Vec3::ONE, Vec3::Z, Vec3::ZERO, Vec3::ONE).unwrap();
        let params = StochasticParams::new(1e-9, 3e-8).unwrap();
        let sphere = Sphere::diffuse(&lobe, &params).unwrap();
        assert!(sphere.is_empty() && !sphere.contains(Vec3::ONE));
        assert!(sphere.center.is_finite());
        let nan = Sphere {
            center: Vec3::ZERO,
            radius: f32::NAN,
        };
        assert!(nan.is_empty() && !nan.contains(Vec3::ZERO));
    }

    #[test]
    fn contains_handles_extreme_coordinates() {
        let s = Sphere {
            center: Vec3::ZERO,
            radius: 1e30,
        };
        assert!(s.contains(Vec3::splat(5e29)));
        assert!(!s.contains(Vec3::splat(6e29)));
        assert!(!s.contains(Vec3::splat(f32::MAX)));
    }
}
