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
    /// `clamp((cos - cos_outer) / (cos_inner - cos_outer), 0, 1)^2` ([`SpotCone`]), a hard
    /// edge where the angles are equal.
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
        self.emitter().incident(x)
    }

    /// Angular falloff of a spot light in the unit direction `emitted` (1 for other
    /// lights): [`SpotCone::falloff`] of `1 − cos` of its angle to the axis.
    pub fn spot_falloff(&self, emitted: Vec3) -> f32 {
        self.emitter().spot_falloff(emitted)
    }

    /// This light made ready for [`Emitter::incident`] at many points: a spot light's cone
    /// (two sines) formed once, not at every point. The same values as [`Light::incident`]
    /// and [`Light::spot_falloff`].
    pub fn emitter(&self) -> Emitter<'_> {
        Emitter {
            light: self,
            cone: self.spot_cone(),
        }
    }

    /// A spot light's axis and [`SpotCone`]; `None` for other lights.
    pub fn spot_cone(&self) -> Option<(Vec3, SpotCone)> {
        match *self {
            Light::Spot {
                direction,
                inner_cone_angle,
                outer_cone_angle,
                ..
            } => Some((direction, SpotCone::new(inner_cone_angle, outer_cone_angle))),
            _ => None,
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
                        && outer_cone_angle > 0.0
                        && outer_cone_angle <= std::f32::consts::FRAC_PI_2;
                    (!ok).then(|| format!("cone angles {inner_cone_angle} (inner) and {outer_cone_angle} (outer) are not 0 <= inner <= outer <= pi/2 with outer above 0 (a cone of 0 emits nothing)"))
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

/// The spot falloff of `KHR_lights_punctual`, `t²` with `t = clamp((cos θ − cos θo) /
/// (cos θi − cos θo), 0, 1)` for the angle θ to the axis, evaluated without cancellation for
/// cones of any width: with `h(θ) = 1 − cos θ = 2 sin²(θ/2)`, `t = (h(θo) − h(θ)) / (h(θo) −
/// h(θi))`, and `h` of a direction comes from the chord to the axis ([`one_minus_cos`]). In
/// `f32`, `cos θ` is 1 for every θ below 0.014° (and the specification's reference code
/// clamps `cos θi − cos θo` at 1e-3, which dims every cone narrower than about 2.6°); `h` keeps
/// its relative precision down to θ ≈ 1e-6. Equal angles give a hard edge (1 inside, 0 from
/// the edge on): the limit of the ramp.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotCone {
    /// `h(θo)`.
    pub h_outer: f32,
    /// `h(θo) − h(θi)` (0 for a hard edge).
    pub h_width: f32,
}

/// A [`Light`] with its spot cone formed ([`Light::emitter`]).
#[derive(Clone, Copy, Debug)]
pub struct Emitter<'a> {
    light: &'a Light,
    cone: Option<(Vec3, SpotCone)>,
}

impl Emitter<'_> {
    /// The light.
    pub fn light(&self) -> &Light {
        self.light
    }

    /// [`Light::incident`].
    pub fn incident(&self, x: Vec3) -> Option<Incident> {
        match *self.light {
            Light::Point {
                position,
                intensity,
            } => point_incident(position, intensity, x),
            Light::Spot {
                position,
                intensity,
                ..
            } => {
                let inc = point_incident(position, intensity, x)?;
                let falloff = self.spot_falloff(-inc.omega_i);
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

    /// [`Light::spot_falloff`].
    pub fn spot_falloff(&self, emitted: Vec3) -> f32 {
        self.cone.map_or(1.0, |(axis, cone)| {
            cone.falloff(one_minus_cos(emitted, axis))
        })
    }
}

impl SpotCone {
    pub fn new(inner_cone_angle: f32, outer_cone_angle: f32) -> Self {
        let h = |angle: f32| 2.0 * (0.5 * angle).sin().powi(2);
        let h_outer = h(outer_cone_angle);
        Self {
            h_outer,
            h_width: (h_outer - h(inner_cone_angle)).max(0.0),
        }
    }

    /// The falloff at `h = 1 − cos θ`.
    pub fn falloff(&self, h: f32) -> f32 {
        if self.h_width > 0.0 {
            let t = ((self.h_outer - h) / self.h_width).clamp(0.0, 1.0);
            t * t
        } else {
            f32::from(u8::from(h < self.h_outer))
        }
    }
}

/// `1 − cos θ` between the unit vectors `a` and `b`, as half the squared chord `|a − b|²/2`:
/// exact to the rounding of the chord where `1 − a·b` cancels.
pub fn one_minus_cos(a: Vec3, b: Vec3) -> f32 {
    0.5 * (a - b).length_squared()
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

    fn spot(inner_deg: f32, outer_deg: f32) -> Light {
        Light::Spot {
            position: Vec3::ZERO,
            direction: Vec3::NEG_Y,
            intensity: Vec3::ONE,
            inner_cone_angle: inner_deg.to_radians(),
            outer_cone_angle: outer_deg.to_radians(),
        }
    }

    /// The direction at `deg` degrees from the spot's axis (-y), tilted towards +x.
    fn at_angle(deg: f64) -> Vec3 {
        let t = deg.to_radians();
        glam::DVec3::new(t.sin(), -t.cos(), 0.0).as_vec3()
    }

    #[test]
    fn on_the_axis_every_cone_gives_the_point_light() {
        // The cones: 2°, 1° and 0.01° (inner 0) gave 0.37, 0.023 and 0 of the point
        // light on the axis; hard edges too.
        for (inner, outer) in [
            (0.0, 2.0),
            (0.0, 1.0),
            (0.0, 0.01),
            (0.01, 0.01),
            (45.0, 90.0),
        ] {
            let s = spot(inner, outer);
            let x = Vec3::new(0.0, -3.0, 0.0);
            let point = Light::Point {
                position: Vec3::ZERO,
                intensity: Vec3::ONE,
            };
            let (a, b) = (s.incident(x).unwrap(), point.incident(x).unwrap());
            assert_eq!(a.irradiance, b.irradiance, "{inner}° {outer}°");
        }
    }

    #[test]
    fn the_falloff_is_the_specifications_curve_in_double_precision() {
        // t² with t = (cos θ − cos θo)/(cos θi − cos θo), against f64, for cones from 0.01°
        // to 90° and angles across and beyond the ramp.
        for (inner, outer) in [
            (0.0, 0.01),
            (0.002, 0.01),
            (0.0, 1.0),
            (0.5, 2.0),
            (10.0, 45.0),
            (0.0, 90.0),
        ] {
            let s = spot(inner, outer);
            let (ci, co) = (
                f64::from(inner).to_radians().cos(),
                f64::from(outer).to_radians().cos(),
            );
            for k in 0..=60 {
                let theta = f64::from(outer) * f64::from(k) / 50.0;
                let want = ((theta.to_radians().cos() - co) / (ci - co))
                    .clamp(0.0, 1.0)
                    .powi(2);
                let got = f64::from(s.spot_falloff(at_angle(theta)));
                // The ramp's slope times the direction's rounding (a relative 1e-7 of θ).
                let slack = 2e-3 * (theta / f64::from(outer - inner)).max(1.0);
                assert!(
                    (got - want).abs() <= slack,
                    "{inner}°..{outer}° at {theta}°: {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn a_hard_edge_is_one_inside_and_zero_outside() {
        let s = spot(0.01, 0.01);
        assert_eq!(s.spot_falloff(at_angle(0.0099)), 1.0);
        assert_eq!(s.spot_falloff(at_angle(0.0101)), 0.0);
        assert!(s.is_valid());
        // A cone of 0 emits nothing: refused.
        assert!(spot(0.0, 0.0).problem().unwrap().contains("outer above 0"));
    }
}
