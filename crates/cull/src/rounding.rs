//! f64 values rounded to the f32 on one side of them: the limits of the f32 lane tests, which
//! may only grow (or, for a limit that passes, only shrink) when rounded.

/// `x` rounded to an f32 not below it (NaN stays NaN, beyond f32's range infinity).
pub(crate) fn up(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) < x {
        y.next_up()
    } else {
        y
    }
}

/// `x` rounded to an f32 not above it (NaN stays NaN, beyond f32's range minus infinity).
pub(crate) fn down(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) > x {
        y.next_down()
    } else {
        y
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounds_to_the_side_asked() {
        for x in [
            0.1,
            -0.1,
            1.0,
            1e-50,
            -1e-50,
            1e300,
            -1e300,
            f64::from(f32::MAX) * 1.5,
        ] {
            let (u, d) = (up(x), down(x));
            assert!(f64::from(u) >= x && f64::from(d) <= x, "{x}: {u} {d}");
            assert!(u == d || u == d.next_up(), "{x}: {u} {d}");
        }
        assert_eq!((up(0.5), down(0.5)), (0.5, 0.5));
        assert!(up(f64::NAN).is_nan() && down(f64::NAN).is_nan());
    }
}
