//! Analytic light sources in radiometric units.
use glam::Vec3;

/// A light source. Units are radiometric and per RGB channel: point and spot lights give
/// radiant intensity in W/sr (glTF `KHR_lights_punctual` intensity is read as W/sr, not
/// candela), a directional light gives irradiance in W/m^2 on a surface facing it.
#[derive(Clone, Debug, PartialEq)]
pub enum Light {
    Point {
        position: Vec3,
        intensity: Vec3,
    },
    /// A spot light with the smooth angular falloff of `KHR_lights_punctual`:
    /// `clamp((cos - cos_outer) / (cos_inner - cos_outer), 0, 1)^2`.
    Spot {
        position: Vec3,
        /// Unit direction the spot points to.
        direction: Vec3,
        intensity: Vec3,
        inner_cone_angle: f32,
        outer_cone_angle: f32,
    },
    Directional {
        /// Unit direction the light travels in.
        direction: Vec3,
        irradiance: Vec3,
    },
}

/// Light arriving at a point from one light source.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Incident {
    /// Unit direction from the point towards the light.
    pub omega_i: Vec3,
    /// Distance to the light (infinite for directional lights).
    pub distance: f32,
    /// Irradiance on a surface facing the light, E = I / d^2 (W/m^2 per channel);
    /// multiply by the cosine at the receiver.
    pub irradiance: Vec3,
}

impl Light {
    /// Light from this source at `x`, without visibility. `None` where it delivers nothing
    /// (outside a spot cone, at the light's own position).
    pub fn incident(&self, x: Vec3) -> Option<Incident> {
        match *self {
            Light::Point {
                position,
                intensity,
            } => point_incident(position, intensity, x),
            Light::Spot {
                position,
                direction,
                intensity,
                ..
            } => {
                let inc = point_incident(position, intensity, x)?;
                let falloff = self.spot_falloff(-inc.omega_i.dot(direction));
                (falloff > 0.0).then(|| Incident {
                    irradiance: inc.irradiance * falloff,
                    ..inc
                })
            }
            Light::Directional {
                direction,
                irradiance,
            } => Some(Incident {
                omega_i: -direction,
                distance: f32::INFINITY,
                irradiance,
            }),
        }
    }

    /// Angular falloff of a spot light for the cosine between its axis and the emitted
    /// direction (1 for other lights).
    pub fn spot_falloff(&self, cos_axis: f32) -> f32 {
        match *self {
            Light::Spot {
                inner_cone_angle,
                outer_cone_angle,
                ..
            } => {
                let (ci, co) = (inner_cone_angle.cos(), outer_cone_angle.cos());
                let t = ((cos_axis - co) / (ci - co).max(1e-3)).clamp(0.0, 1.0);
                t * t
            }
            _ => 1.0,
        }
    }

    /// Whether [`Light::problem`] finds nothing wrong.
    pub fn is_valid(&self) -> bool {
        self.problem().is_none()
    }

    /// What makes the light unusable, if anything: a non-finite position or direction, a
    /// negative or non-finite value, a value above [`MAX_RADIOMETRIC`], or spot cone angles
    /// outside `0 <= inner <= outer <= π/2`.
    pub fn problem(&self) -> Option<String> {
        let value = |what: &str, v: Vec3| {
            (!(v.is_finite() && v.min_element() >= 0.0 && v.max_element() <= MAX_RADIOMETRIC))
                .then(|| format!("{what} [{:e}, {:e}, {:e}] is not in [0, {MAX_RADIOMETRIC:e}] per channel (larger values overflow f32 in the renderer's products)", v.x, v.y, v.z))
        };
        let position = |p: Vec3| (!p.is_finite()).then(|| format!("position {p} is not finite"));
        let direction =
            |d: Vec3| (!d.is_normalized()).then(|| format!("direction {d} is not a unit vector"));
        match *self {
            Light::Point {
                position: p,
                intensity,
            } => position(p).or_else(|| value("intensity", intensity)),
            Light::Spot {
                position: p,
                direction: d,
                intensity,
                inner_cone_angle,
                outer_cone_angle,
            } => position(p)
                .or_else(|| direction(d))
                .or_else(|| value("intensity", intensity))
                .or_else(|| {
                    let ok = inner_cone_angle >= 0.0
                        && inner_cone_angle <= outer_cone_angle
                        && outer_cone_angle <= std::f32::consts::FRAC_PI_2;
                    (!ok).then(|| format!("cone angles {inner_cone_angle} (inner) and {outer_cone_angle} (outer) are not 0 <= inner <= outer <= pi/2"))
                }),
            Light::Directional {
                direction: d,
                irradiance,
            } => direction(d).or_else(|| value("irradiance", irradiance)),
        }
    }

    /// `point`, `spot` or `directional`.
    pub fn kind(&self) -> &'static str {
        match self {
            Light::Point { .. } => "point",
            Light::Spot { .. } => "spot",
            Light::Directional { .. } => "directional",
        }
    }
}

/// The largest radiant intensity (W/sr) or irradiance (W/m²) per channel a light may have:
/// 1e20, which leaves f32 (max 3.4e38) eighteen orders of magnitude for the products the
/// renderer forms with it (the GGX peak 1/(π α²) ≤ 3.2e7 at the smallest α, 1/d² of nearby
/// receivers, the flux of an RSM texel). Beyond that a pixel can overflow to infinity, which
/// the render then reports as [`crate::frame::RenderError::NonFinite`].
pub const MAX_RADIOMETRIC: f32 = 1e20;

fn point_incident(position: Vec3, intensity: Vec3, x: Vec3) -> Option<Incident> {
    let to_light = position - x;
    let d2 = to_light.length_squared();
    (d2 > 0.0).then(|| {
        let distance = d2.sqrt();
        Incident {
            omega_i: to_light / distance,
            distance,
            irradiance: intensity / d2,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_square_law() {
        let l = Light::Point {
            position: Vec3::new(0.0, 2.0, 0.0),
            intensity: Vec3::splat(5.0),
        };
        let inc = l.incident(Vec3::ZERO).unwrap();
        assert_eq!(inc.omega_i, Vec3::Y);
        assert!((inc.irradiance.x - 1.25).abs() < 1e-6);
        assert!(l.incident(Vec3::new(0.0, 2.0, 0.0)).is_none());
    }

    #[test]
    fn spot_cone() {
        let l = Light::Spot {
            position: Vec3::ZERO,
            direction: Vec3::NEG_Y,
            intensity: Vec3::ONE,
            inner_cone_angle: 0.2,
            outer_cone_angle: 0.4,
        };
        assert!((l.incident(Vec3::new(0.0, -1.0, 0.0)).unwrap().irradiance.x - 1.0).abs() < 1e-6);
        assert!(l.incident(Vec3::new(1.0, -1.0, 0.0)).is_none());
        let mid = l.incident(Vec3::new(0.3f32.tan(), -1.0, 0.0)).unwrap();
        assert!(mid.irradiance.x > 0.0 && mid.irradiance.x < 1.0);
        assert!(l.is_valid());
    }
}
