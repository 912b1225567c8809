//! Textures in linear RGB, sampled bilinearly with wrap-around addressing.
use glam::{Vec2, Vec3};

/// Index of a texture in `Scene::textures`.
pub type TextureId = usize;

/// An RGB texture of linear values (sRGB-encoded files are decoded on load).
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    pub name: String,
    pub width: u32,
    pub height: u32,
    /// Row-major texels, row 0 at v = 0 (the top of the image file).
    pub texels: Vec<Vec3>,
}

impl Texture {
    /// Bilinear lookup with repeat wrapping; (0,0) is the image's top-left as in glTF (the OBJ
    /// loader flips v on load to match).
    pub fn sample(&self, uv: Vec2) -> Vec3 {
        let (w, h) = (self.width as i64, self.height as i64);
        if w == 0 || h == 0 || !uv.is_finite() {
            return Vec3::ONE;
        }
        let x = uv.x * self.width as f32 - 0.5;
        let y = uv.y * self.height as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        // The four texels wrapped once each way (two remainders, not eight).
        let wrap = |i: i64, n: i64| {
            let i0 = i.rem_euclid(n);
            (i0 as usize, if i0 + 1 == n { 0 } else { i0 as usize + 1 })
        };
        let ((x0, x1), (y0, y1)) = (wrap(x0 as i64, w), wrap(y0 as i64, h));
        let row = |y: usize| &self.texels[y * w as usize..(y + 1) * w as usize];
        let (r0, r1) = (row(y0), row(y1));
        let top = r0[x0].lerp(r0[x1], fx);
        let bottom = r1[x0].lerp(r1[x1], fx);
        top.lerp(bottom, fy)
    }
}

/// The sRGB electro-optical transfer function: an 8-bit-style encoded value to linear.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_and_wrap() {
        let t = Texture {
            name: "t".into(),
            width: 2,
            height: 1,
            texels: vec![Vec3::ZERO, Vec3::ONE],
        };
        assert_eq!(t.sample(Vec2::new(0.25, 0.5)), Vec3::ZERO);
        assert_eq!(t.sample(Vec2::new(0.75, 0.5)), Vec3::ONE);
        assert!((t.sample(Vec2::new(0.5, 0.5)).x - 0.5).abs() < 1e-6);
        assert_eq!(t.sample(Vec2::new(1.25, 0.5)), Vec3::ZERO);
    }

    #[test]
    fn srgb_endpoints() {
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-6);
        assert!((srgb_to_linear(0.5) - 0.214).abs() < 1e-3);
    }
}
