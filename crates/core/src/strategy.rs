//! The culling strategies, typed: one name table for the command line, the CPU cullers
//! (`slc_cull::culler`) and the GPU cullers (`slc_gpu_wgpu::cull`).
use std::fmt;
use std::str::FromStr;

/// Which bound a glossy VPL is culled with; diffuse VPLs always use the sphere of section 6.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GlossyBound {
    /// The sphere of radius r/α around the VPL position q (section 7, after Tokuyoshi and
    /// Harada 2016: the maximum of s(ωo) in eq. (12)).
    Sphere,
    /// The sphere of radius r_u around the spheroid's centre c, enclosing the spheroid
    /// (section 7).
    EnclosingSphere,
    /// The GGX bounding spheroid of eq. (12)-(15), tested as a unit sphere in its stretched
    /// and rotated space (eq. 16-17).
    Ellipsoid,
    /// The spheroid, then per 4×4 block of a tile's pixels and depth cluster a bound of p over
    /// the block's receivers (`slc_bounds::BoxBound`: every factor of the intensity bounded
    /// over the cone of directions to them, the VPL's tangent plane included); diffuse VPLs'
    /// spheres refined the same way (docs/tight-bounds.md).
    Tight,
}

/// How a strategy groups pixels before testing bounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Layout {
    /// No culling: every VPL of the pixel's interleaved subregion (section 6).
    Unculled,
    /// 16×16 tiles of each subregion image, two depth clusters per tile (Modified HalfZ,
    /// section 5.1).
    Tiled,
    /// The same tiles cut into 32 exponential depth slices (section 7).
    Clustered,
    /// No lists: each VPL's bounding mesh is drawn over its subregion's pixels and shades the
    /// pixels it covers, blended additively (splatting, Dachsbacher and Stamminger 2006; the
    /// paper's Table 2 baseline). GPU only.
    Splatting,
    /// The clustered grid of [`Layout::Clustered`] filled by rasterizing each VPL's bounding
    /// mesh at tile resolution, conservatively, into a linked-list node buffer (Örtegren and
    /// Persson 2016; the paper's Table 2 baseline). GPU only.
    ClusteredRaster,
    /// Scatter instead of gather (docs/many-vpls.md): each VPL's bound is binned, by the
    /// rectangle of screen pixels it covers, into the 16×16 tiles of its subregion image that
    /// rectangle overlaps, and each pixel of a tile tests its own G-buffer point against the
    /// bounds of its tile's bin: a list per pixel, at a cost of the VPLs plus the pixels their
    /// rectangles cover, not VPLs × tiles (the paper's open problem, section 8). On the CPU,
    /// a rectangle larger than a tile is tested per 4×4 cell instead, into a list the cell's
    /// pixels share (`LightLists::shared_list`).
    Binned,
}

/// A culling strategy: a [`Layout`] and, unless unculled, the [`GlossyBound`] of glossy VPLs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Strategy {
    None,
    Sphere,
    EnclosingSphere,
    Ellipsoid,
    Clustered,
    ClusteredSphere,
    ClusteredEnclosingSphere,
    Tight,
    ClusteredTight,
    Splatting,
    ClusteredRaster,
    Binned,
}

/// A strategy name that names no strategy.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown culling strategy '{name}' (one of {})", Strategy::names().join(", "))]
pub struct UnknownStrategy {
    pub name: String,
}

impl Strategy {
    /// Every strategy with a culler on both backends (lists the CPU culler `slc_cull::culler`
    /// and the GPU's compute cullers build), in the order tables list them.
    pub const ALL: [Strategy; 10] = [
        Strategy::None,
        Strategy::Sphere,
        Strategy::EnclosingSphere,
        Strategy::Ellipsoid,
        Strategy::Clustered,
        Strategy::ClusteredSphere,
        Strategy::ClusteredEnclosingSphere,
        Strategy::Tight,
        Strategy::ClusteredTight,
        Strategy::Binned,
    ];

    /// The GPU's rasterization baselines of the paper's Table 2 (splatting \[DS06\], clustered
    /// shading by conservative rasterization \[OP16\]): no CPU culler.
    pub const RASTER: [Strategy; 2] = [Strategy::Splatting, Strategy::ClusteredRaster];

    /// [`Self::ALL`], then [`Self::RASTER`].
    pub fn every() -> impl Iterator<Item = Strategy> {
        Self::ALL.into_iter().chain(Self::RASTER)
    }

    /// Every strategy with a CPU culler: [`Self::ALL`] (the raster baselines have none).
    pub fn on_cpu() -> impl Iterator<Item = Strategy> {
        Self::ALL.into_iter()
    }

    /// Whether the strategy rasterizes bounding meshes ([`Self::RASTER`]).
    pub fn is_raster(self) -> bool {
        matches!(self.parts().0, Layout::Splatting | Layout::ClusteredRaster)
    }

    /// The name as the command line, reports and tables spell it.
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Sphere => "sphere",
            Self::EnclosingSphere => "enclosing-sphere",
            Self::Ellipsoid => "ellipsoid",
            Self::Clustered => "clustered",
            Self::ClusteredSphere => "clustered-sphere",
            Self::ClusteredEnclosingSphere => "clustered-enclosing-sphere",
            Self::Tight => "tight",
            Self::ClusteredTight => "clustered-tight",
            Self::Splatting => "splatting",
            Self::ClusteredRaster => "clustered-raster",
            Self::Binned => "binned",
        }
    }

    /// Every strategy's name, in the order of [`Self::every`].
    pub fn names() -> Vec<&'static str> {
        Self::every().map(|s| s.name()).collect()
    }

    /// The layout and the glossy bound (`Ellipsoid` for the unculled layout, where no bound
    /// is tested; the raster baselines draw the spheroid for glossy VPLs as the paper's
    /// Table 2 does).
    pub fn parts(self) -> (Layout, GlossyBound) {
        use GlossyBound::{Ellipsoid, EnclosingSphere, Sphere, Tight};
        match self {
            Self::None => (Layout::Unculled, Ellipsoid),
            Self::Sphere => (Layout::Tiled, Sphere),
            Self::EnclosingSphere => (Layout::Tiled, EnclosingSphere),
            Self::Ellipsoid => (Layout::Tiled, Ellipsoid),
            Self::Clustered => (Layout::Clustered, Ellipsoid),
            Self::ClusteredSphere => (Layout::Clustered, Sphere),
            Self::ClusteredEnclosingSphere => (Layout::Clustered, EnclosingSphere),
            Self::Tight => (Layout::Tiled, Tight),
            Self::ClusteredTight => (Layout::Clustered, Tight),
            Self::Splatting => (Layout::Splatting, Ellipsoid),
            Self::ClusteredRaster => (Layout::ClusteredRaster, Ellipsoid),
            Self::Binned => (Layout::Binned, Ellipsoid),
        }
    }
}

impl FromStr for Strategy {
    type Err = UnknownStrategy;

    fn from_str(name: &str) -> Result<Self, Self::Err> {
        Self::every()
            .find(|s| s.name() == name)
            .ok_or_else(|| UnknownStrategy { name: name.into() })
    }
}

impl fmt::Display for Strategy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_parse_back_and_are_distinct() {
        for s in Strategy::every() {
            assert_eq!(s.name().parse::<Strategy>(), Ok(s));
            assert_eq!(s.to_string(), s.name());
        }
        let mut names = Strategy::names();
        names.dedup();
        assert_eq!(names.len(), Strategy::ALL.len() + Strategy::RASTER.len());
        assert!(Strategy::RASTER.iter().all(|s| s.is_raster()));
        assert!(!Strategy::on_cpu().any(|s| s.is_raster()));
        let parts: std::collections::HashSet<_> = Strategy::on_cpu()
            .filter(|s| s.parts().0 != Layout::Unculled)
            .map(|s| s.parts())
            .collect();
        assert_eq!(
            parts.len(),
            Strategy::on_cpu().count() - 1,
            "one strategy per layout and bound"
        );
    }

    #[test]
    fn an_unknown_name_lists_the_known_ones() {
        let e = "bogus".parse::<Strategy>().unwrap_err();
        assert_eq!(e.name, "bogus");
        assert!(e.to_string().contains("ellipsoid, clustered"), "{e}");
    }
}
