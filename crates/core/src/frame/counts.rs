//! The range of every count a frame or a command takes, defined once for every front end:
//! [`super::RenderSettings::validate`], the command line's value parsers and `--help`, and
//! the Python options all read these.
use std::fmt;

/// A count and its inclusive range.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Count {
    /// What it counts, as messages name it ("spp", "the width").
    pub what: &'static str,
    pub min: u32,
    pub max: u32,
}

impl Count {
    /// A count from 1 to `max`.
    pub const fn up_to(what: &'static str, max: u32) -> Count {
        Count { what, min: 1, max }
    }

    /// `value`, or an error naming the count and its range.
    pub fn check(&self, value: u32) -> Result<u32, String> {
        if (self.min..=self.max).contains(&value) {
            Ok(value)
        } else {
            Err(format!("{} must be in {self} (got {value})", self.what))
        }
    }

    /// A help text with the range appended.
    pub fn help(&self, text: &str) -> String {
        format!("{text} [{self}]")
    }
}

impl fmt::Display for Count {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}..={}", self.min, self.max)
    }
}

/// The largest image side and RSM side a frame accepts.
pub const MAX_IMAGE_SIDE: u32 = 16384;
pub const MAX_RSM_SIDE: u32 = 4096;
/// The largest number of sampled lights (or camera-side VSGLs) a frame accepts.
pub const MAX_SAMPLED_LIGHTS: u32 = 1 << 24;

pub const WIDTH: Count = Count::up_to("the width", MAX_IMAGE_SIDE);
pub const HEIGHT: Count = Count::up_to("the height", MAX_IMAGE_SIDE);
pub const RSM: Count = Count::up_to("the RSM resolution", MAX_RSM_SIDE);
/// Passes averaged: beyond 2^16 the f32 sum of the passes loses more than 2^-8 of each
/// pass's weight, and the run takes days.
pub const SPP: Count = Count::up_to("spp", 1 << 16);
pub const INTERLEAVE: Count = Count::up_to("the interleaving K", 64);
pub const SAMPLED_LIGHTS: Count =
    Count::up_to("the number of sampled lights (VSGLs)", MAX_SAMPLED_LIGHTS);
pub const CAMERA_VSGLS: Count = Count::up_to("the number of camera VSGLs", MAX_SAMPLED_LIGHTS);
/// Timed repetitions (`--repeat`).
pub const REPEAT: Count = Count::up_to("the number of repetitions", 1000);
/// Point sets of a VSGL sweep (`--seeds`).
pub const SEEDS: Count = Count::up_to("the number of seeds", 1000);
/// The heat map's saturation in lights per pixel (`--heat-max`).
pub const HEAT_MAX: Count = Count::up_to("the heat map's maximum", 1 << 24);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_count_out_of_range_names_itself_and_its_range() {
        assert_eq!(SPP.check(4), Ok(4));
        assert_eq!(
            SPP.check(0).unwrap_err(),
            "spp must be in 1..=65536 (got 0)"
        );
        assert!(SPP.check(4_294_967_295).unwrap_err().contains("1..=65536"));
        assert_eq!(SPP.help("Passes."), "Passes. [1..=65536]");
    }
}
