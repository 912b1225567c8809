//! The GGX bounding spheroid of a glossy VPL, eq. (12)-(15).
use crate::basis::Basis;
use crate::check;
use crate::error::BoundsError;
use crate::glossy::GlossyLobe;
use crate::stochastic::StochasticParams;
use glam::{Mat3, Vec3};

/// Below this |ω_u × n|² (sin θi < 1e-3) ω_w of eq. (14) is taken from a [`Basis`] around ω_u
/// instead of the ill-conditioned cross product: the spheroid is symmetric about ω_u
/// (r_v = r_w), so any unit vector orthogonal to ω_u is as good.
const MIN_CROSS_SQ: f32 = 1e-6;

/// The spheroid of eq. (12)-(15) enclosing the random range l_max(ωo) of eq. (5) of a glossy
/// VPL in every direction: semi-axes (r_u, r_v, r_w) = ((1+α²)/(2α) r, r, r) along the columns
/// (ω_u, ω_w × ω_u, ω_w) of the rotation R, centred at c = q + (1−α²)/(2α) r ω_u.
///
/// With r = 0 (ωi·n <= 0 or zero flux) the spheroid is empty: it contains nothing, not even
/// q, which culls the light everywhere (p = 0 > ξ never holds).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spheroid {
    center: Vec3,
    rotation: Mat3,
    semi_axes: Vec3,
    radius: f32,
}

impl Spheroid {
    /// Builds the spheroid of eq. (12)-(15) for `lobe` and the light's δ, ξ. Fails only with
    /// [`BoundsError::Overflow`] when the extreme inputs put a semi-axis or the centre
    /// outside the `f32` range.
    pub fn new(lobe: &GlossyLobe, params: &StochasticParams) -> Result<Self, BoundsError> {
        let r = f64::from(lobe.radius(params)?);
        let alpha = f64::from(lobe.alpha());
        let omega_u = lobe.reflection();
        let r_u = check::fits((1.0 + alpha * alpha) / (2.0 * alpha) * r, "semi-axis r_u")?;
        let offset = check::fits((1.0 - alpha * alpha) / (2.0 * alpha) * r, "spheroid centre")?;
        let center = check::fits_vec(lobe.position() + offset * omega_u, "spheroid centre")?;
        Ok(Self {
            center,
            rotation: rotation(omega_u, lobe.normal()),
            semi_axes: Vec3::new(r_u, r as f32, r as f32),
            radius: r as f32,
        })
    }

    /// The centre c of eq. (15).
    #[inline]
    pub fn center(&self) -> Vec3 {
        self.center
    }

    /// The rotation R = [ω_u, ω_w × ω_u, ω_w] of eq. (14) (columns; orthonormal, det +1).
    #[inline]
    pub fn rotation(&self) -> Mat3 {
        self.rotation
    }

    /// The semi-axes (r_u, r_v, r_w) of eq. (13), along the columns of [`Self::rotation`].
    #[inline]
    pub fn semi_axes(&self) -> Vec3 {
        self.semi_axes
    }

    /// The radius r of eq. (12) (= r_v = r_w); 0 for an empty spheroid.
    #[inline]
    pub fn radius(&self) -> f32 {
        self.radius
    }

    /// Whether the spheroid of eq. (12)-(15) is empty (r = 0).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.radius <= 0.0
    }

    /// Whether `point` lies in the closed spheroid of eq. (12)-(15):
    /// `Σ ((p − c)·R_k / r_k)² <= 1`. Always false for an empty spheroid. Each coordinate is
    /// divided before squaring, so no intermediate overflows.
    #[inline]
    pub fn contains(&self, point: Vec3) -> bool {
        if self.is_empty() {
            return false;
        }
        let s = self.rotation.transpose() * (point - self.center) / self.semi_axes;
        s.abs().max_element() <= 1.0 && s.length_squared() <= 1.0
    }
}

/// R = [ω_u, ω_w × ω_u, ω_w] of eq. (14), ω_w = ω_u × n / |ω_u × n| (or any unit vector
/// orthogonal to ω_u at normal incidence), re-orthogonalised so R is a rotation to rounding.
fn rotation(omega_u: Vec3, normal: Vec3) -> Mat3 {
    let cross = omega_u.cross(normal);
    let len_sq = cross.length_squared();
    let omega_w = if len_sq > MIN_CROSS_SQ {
        cross / len_sq.sqrt()
    } else {
        Basis::from_unit(omega_u).x
    };
    let omega_v = omega_w.cross(omega_u).normalize();
    Mat3::from_cols(omega_u, omega_v, omega_u.cross(omega_v))
}

#[cfg(test)]
mod conservative_tests;
#[cfg(test)]
mod probe;
#[cfg(test)]
mod tests;
