//! Deterministic sampling helpers shared by the unit tests.
use glam::Vec3;

/// A small SplitMix64 generator, so the dense test loops are reproducible.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    pub fn u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn f64(&mut self) -> f64 {
        (self.u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [0, 1).
    pub fn f32(&mut self) -> f32 {
        self.f64() as f32
    }

    /// An input for the lane types' bit-for-bit tests: one time in four a special value
    /// (signed zeros, subnormals, the largest finite, infinities, NaN), else any bit pattern.
    pub fn lane_input(&mut self) -> f32 {
        const SPECIAL: [f32; 12] = [
            0.0,
            -0.0,
            1.0,
            -1.5,
            f32::MIN_POSITIVE,
            1e-45,
            -1e-40,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            3.0e38,
        ];
        let r = self.u64();
        if r.is_multiple_of(4) {
            SPECIAL[(r >> 8) as usize % SPECIAL.len()]
        } else {
            f32::from_bits((r >> 16) as u32)
        }
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.f32()
    }

    /// Uniform on the unit sphere.
    pub fn unit(&mut self) -> Vec3 {
        let z = 2.0 * self.f64() - 1.0;
        let phi = 2.0 * core::f64::consts::PI * self.f64();
        let s = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, z as f32).normalize()
    }

    /// Uniform on the hemisphere around `n`, strictly above it.
    pub fn above(&mut self, n: Vec3) -> Vec3 {
        loop {
            let v = self.unit();
            let c = v.dot(n);
            if c.abs() > 1e-4 {
                return if c > 0.0 { v } else { -v };
            }
        }
    }
}

/// The k-th of `count` points of a Fibonacci lattice on the unit sphere.
pub fn fibonacci(k: usize, count: usize) -> Vec3 {
    let golden = core::f64::consts::PI * (3.0 - 5f64.sqrt());
    let z = 1.0 - (2.0 * k as f64 + 1.0) / count as f64;
    let s = (1.0 - z * z).max(0.0).sqrt();
    let phi = golden * k as f64;
    Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, z as f32)
}

/// Directions at the given angles (radians) from `axis`, each at `azimuths` evenly spaced
/// azimuths: dense sampling of a neighbourhood of `axis`.
pub fn around(axis: Vec3, angles: &[f64], azimuths: usize) -> Vec<Vec3> {
    let (x, y) = axis.any_orthonormal_pair();
    let (x, y, z) = (x.as_dvec3(), y.as_dvec3(), axis.as_dvec3());
    let mut out = Vec::with_capacity(angles.len() * azimuths);
    for &theta in angles {
        for j in 0..azimuths {
            let phi = 2.0 * core::f64::consts::PI * j as f64 / azimuths as f64;
            let d = z * theta.cos() + (x * phi.cos() + y * phi.sin()) * theta.sin();
            out.push(d.normalize().as_vec3());
        }
    }
    out
}

/// `count` angles spread log-uniformly over [lo, hi].
pub fn log_angles(lo: f64, hi: f64, count: usize) -> Vec<f64> {
    (0..count)
        .map(|k| lo * (hi / lo).powf(k as f64 / (count - 1) as f64))
        .collect()
}

/// A random tangent perpendicular to `n` with α_t from 1e-4 to 1.
pub fn random_anisotropy(rng: &mut Rng, n: Vec3) -> crate::Anisotropy {
    let t = rng.unit();
    crate::Anisotropy {
        tangent: (t - n * n.dot(t))
            .try_normalize()
            .unwrap_or_else(|| n.any_orthonormal_vector()),
        alpha_t: 10f32.powf(rng.range(-4.0, 0.0)),
    }
}

/// What [`lane_operations`] gives: the values as bit patterns (NaN as one pattern: payloads
/// may differ between instructions and scalar code) and the flags, each in lane order, and
/// per mask whether all and whether any of its lanes are set.
pub type LaneResults = (Vec<u32>, Vec<bool>, Vec<[bool; 2]>);

/// Every operation of a lane type (`crate::lanes::Real`) on `x` and `y`, for the lane types'
/// bit-for-bit tests (`values` and `flags` list a vector's lanes).
pub fn lane_operations<R: crate::lanes::Real>(
    x: R,
    y: R,
    values: impl Fn(R) -> Vec<f32>,
    flags: impl Fn(R::Mask) -> Vec<bool>,
) -> LaneResults {
    use crate::lanes::{max, min};
    let m = x.gt(y);
    let results = [
        x + y,
        x - y,
        x * y,
        x / y,
        -x,
        x.sqrt(),
        x.round(),
        x.floor(),
        crate::lanes::exp(x),
        crate::lanes::exp(x * R::splat(1e-37)),
        min(max(x.round(), R::splat(-126.0)), R::splat(127.0)).exp2i(),
        R::select(m, x, y),
        R::select(!m | x.le(y), x, y),
        R::select(m & x.le(y), x, y),
    ];
    let canon = |v: f32| if v.is_nan() { u32::MAX } else { v.to_bits() };
    let bits = results.into_iter().flat_map(values).map(canon).collect();
    let masks = [m, x.le(y), !m, R::flag(true), R::flag(false)];
    let reductions = masks.map(|m| [R::all(m), R::any(m)]).to_vec();
    (
        bits,
        masks.into_iter().flat_map(flags).collect(),
        reductions,
    )
}

/// The eight flags of an eight-lane mask, lane 0 first.
pub fn flags8<L: crate::lanes::Lanes8>(m: L::Mask) -> Vec<bool> {
    (0..8).map(|k| L::bits(m) >> k & 1 == 1).collect()
}
