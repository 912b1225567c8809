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

    /// Whether every number of the light is finite and its intensity non-negative.
    pub fn is_valid(&self) -> bool {
        let ok = |v: Vec3| v.is_finite() && v.min_element() >= 0.0;
        match *self {
            Light::Point {
                position,
                intensity,
            } => position.is_finite() && ok(intensity),
            Light::Spot {
                position,
                direction,
                intensity,
                inner_cone_angle,
                outer_cone_angle,
            } => {
                position.is_finite()
                    && direction.is_normalized()
                    && ok(intensity)
                    && inner_cone_angle >= 0.0
                    && inner_cone_angle <= outer_cone_angle
                    && outer_cone_angle <= std::f32::consts::FRAC_PI_2
            }
            Light::Directional {
                direction,
                irradiance,
            } => direction.is_normalized() && ok(irradiance),
        }
    }
}

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
