//! The stochastic method's options: the traversal of moving triangles (Munkberg 2011,
//! Table 1) and the samples per pixel, split into passes that each fit the sample buffer.

use std::fmt;
use std::str::FromStr;

use raster_hier::{EdgeTest, Footprint, RasterConfig, Traversal};

use super::{BIN, DEFAULT_SPP, MAX_SAMPLES, MAX_SPP};
use crate::error::{Error, Result};

/// The traversal of moving triangles, as chosen with `--traversal` (Munkberg 2011, Table 1).
/// All produce bit-identical images for the same seed; only their cost differs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum TraversalChoice {
    /// OUR: tile tests with temporal bounds, linearised edge test with γ at setup (Eq. 4-9).
    Our,
    /// OUR with the exact edge test (a quadratic per tile corner).
    OurExact,
    /// OUR with the linearised edge test, γ per coarse tile.
    OurPerTile,
    /// OUR with the linearised edge test re-derived per tile at every level, down to 2x2
    /// quads and single pixels below the 4x4 sample-pattern tile (raster-hier's
    /// `RasterConfig::fine()`): the fewest sample tests, more tile tests.
    OurFine,
    /// BBOX: every sample in the swept bounding box.
    Bbox,
    /// CONVEX: tiles against the convex hull of the six projected vertices.
    Convex,
    /// HIERARCHICAL INTERLEAVE: one static traversal per unique sample time.
    Interleave,
    /// OUR (linearised at setup) with the §7 fallback to INTERLEAVE for small, fast
    /// triangles (the default).
    #[default]
    Fallback,
}

impl TraversalChoice {
    /// All choices, in the order `--help` lists them.
    pub const ALL: [TraversalChoice; 8] = [
        TraversalChoice::Our,
        TraversalChoice::OurExact,
        TraversalChoice::OurPerTile,
        TraversalChoice::OurFine,
        TraversalChoice::Bbox,
        TraversalChoice::Convex,
        TraversalChoice::Interleave,
        TraversalChoice::Fallback,
    ];

    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            TraversalChoice::Our => "our",
            TraversalChoice::OurExact => "our-exact",
            TraversalChoice::OurPerTile => "our-per-tile",
            TraversalChoice::OurFine => "our-fine",
            TraversalChoice::Bbox => "bbox",
            TraversalChoice::Convex => "convex",
            TraversalChoice::Interleave => "interleave",
            TraversalChoice::Fallback => "fallback",
        }
    }

    /// The raster-hier traversal.
    pub fn traversal(self) -> Traversal {
        match self {
            TraversalChoice::Our => Traversal::Our(EdgeTest::LinearisedSetup),
            TraversalChoice::OurExact => Traversal::Our(EdgeTest::Exact),
            TraversalChoice::OurPerTile => Traversal::Our(EdgeTest::LinearisedPerTile),
            TraversalChoice::OurFine => Traversal::Our(EdgeTest::LinearisedPerLevel),
            TraversalChoice::Bbox => Traversal::Bbox,
            TraversalChoice::Convex => Traversal::Convex,
            TraversalChoice::Interleave => Traversal::Interleave,
            TraversalChoice::Fallback => Traversal::OurFallback(EdgeTest::LinearisedSetup),
        }
    }

    /// The raster-hier configuration: [`TraversalChoice::traversal`] over the levels
    /// 16 → 8 → 4, or 16 → 8 → 4 → 2 → 1 for [`TraversalChoice::OurFine`].
    pub fn config(self) -> RasterConfig {
        match self {
            TraversalChoice::OurFine => RasterConfig::fine(),
            other => RasterConfig::new(other.traversal()),
        }
    }
}

impl fmt::Display for TraversalChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for TraversalChoice {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Self, Self::Err> {
        crate::names::parse_by_name(s, &TraversalChoice::ALL, TraversalChoice::name, "traversal")
    }
}

/// Options of the stochastic method.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StochasticOptions {
    /// Samples per pixel, a power of two in 1..=[`MAX_SPP`]; `None` = [`DEFAULT_SPP`].
    pub spp: Option<u32>,
    /// Traversal of the moving triangles.
    pub traversal: TraversalChoice,
    /// Seed of the per-tile sample-pattern scrambling.
    pub seed: u64,
    /// Where the samples lie in their pixel: spread over its area (spatial antialiasing,
    /// the default) or at its centre (the pixel-centre quantity accum, analytic and prism
    /// compute; `mblur compare` uses it so that errors measure the same thing).
    pub footprint: Footprint,
    /// The pixel filter of [`Footprint::Area`] ([`crate::aa::Filter`], the one accum,
    /// analytic and prism weight their positions with): each sample counts in every pixel
    /// whose support holds it, weighted by the filter. The box of radius 1/2 (the default)
    /// is the mean over the pixel's own samples.
    pub filter: crate::aa::Filter,
    /// The filter's support radius in pixels, 1/2 to 8 (`None`:
    /// [`crate::aa::Filter::default_radius`]).
    pub filter_radius: Option<f64>,
    /// Most samples one pass may hold, over [`buffer_pixels`] (its buffer costs 12 bytes a
    /// sample); `None` =
    /// [`MAX_SAMPLES`], larger values are capped to it. More samples per pixel than fit are
    /// taken in several passes ([`passes`]).
    pub max_pass_samples: Option<u64>,
}

impl StochasticOptions {
    /// The samples per pixel, checked: a power of two in 1..=[`MAX_SPP`].
    pub fn spp(&self) -> Result<u32> {
        let spp = self.spp.unwrap_or(DEFAULT_SPP);
        if spp == 0 || !spp.is_power_of_two() || spp > MAX_SPP {
            return Err(Error::Setting {
                method: "stochastic",
                setting: "spp",
                message: format!("must be a power of two between 1 and {MAX_SPP}, got {spp}"),
            });
        }
        Ok(spp)
    }

    /// Checks every setting: the samples per pixel ([`StochasticOptions::spp`]) and the
    /// filter's radius (1/2 to 8 pixels); a filter other than the box of radius 1/2 needs
    /// [`Footprint::Area`] (at the pixel centre every sample sits at the same point).
    pub fn validate(&self) -> Result<()> {
        self.spp()?;
        let radius = super::filter::validate(self.filter, self.filter_radius)?;
        if self.footprint == Footprint::Centre
            && (self.filter != crate::aa::Filter::Box || radius != 0.5)
        {
            return Err(Error::Setting {
                method: "stochastic",
                setting: "filter",
                message: format!(
                    "{} of radius {radius} needs the area footprint: with the centre \
                     footprint every sample sits at its pixel centre",
                    self.filter
                ),
            });
        }
        Ok(())
    }

    /// The filter's support radius in use.
    pub fn filter_radius(&self) -> f64 {
        self.filter_radius.unwrap_or(self.filter.default_radius())
    }

    /// The most samples one pass may hold: [`StochasticOptions::max_pass_samples`] capped
    /// to [`MAX_SAMPLES`].
    pub fn pass_limit(&self) -> u64 {
        self.max_pass_samples
            .map_or(MAX_SAMPLES, |l| l.min(MAX_SAMPLES))
    }

    /// The sample passes a `width` x `height` render takes with these options: [`passes`]
    /// with the checked [`StochasticOptions::spp`] and [`StochasticOptions::pass_limit`].
    pub fn passes(&self, width: u32, height: u32) -> Result<u32> {
        passes(width, height, self.spp()?, self.pass_limit())
    }
}

/// The pixels a W x H sample buffer holds: raster-hier allocates whole [`BIN`] x [`BIN`]
/// bins, so each side is rounded up to a multiple of [`BIN`].
pub fn buffer_pixels(width: u32, height: u32) -> u64 {
    let padded = |n: u32| u64::from(n).div_ceil(u64::from(BIN)) * u64::from(BIN);
    padded(width) * padded(height)
}

/// Sample passes for W x H pixels at S samples (a power of two) with at most `limit`
/// samples a pass, counting the samples the buffer really holds (N = [`buffer_pixels`]):
/// 1 when N x S fits, else the smallest power of two P with N x S / P within it. An error
/// when even one sample per pixel does not fit.
pub fn passes(width: u32, height: u32, spp: u32, limit: u64) -> Result<u32> {
    let pixels = buffer_pixels(width, height);
    if pixels > limit || spp == 0 {
        // Below MAX_SAMPLES the limit was lowered by `max_pass_samples`.
        let setting = if limit < MAX_SAMPLES {
            "max_pass_samples"
        } else {
            "spp"
        };
        return Err(Error::Setting {
            method: "stochastic",
            setting,
            message: format!(
                "{width} x {height} pixels ({pixels} in the sample buffer's whole \
                 {BIN}-pixel bins) x {spp} samples: a pass holds at most {limit} samples, not \
                 even 1 sample per pixel fits"
            ),
        });
    }
    let mut passes = 1u32;
    while pixels * u64::from(spp / passes) > limit {
        passes *= 2;
    }
    Ok(passes)
}

#[cfg(test)]
mod tests {
    use super::super::{TILE, ZMAX_SLICES};
    use super::*;
    use raster_hier::SampleBuffer;

    #[test]
    fn traversal_names_round_trip() {
        for t in TraversalChoice::ALL {
            assert_eq!(t.name().parse::<TraversalChoice>(), Ok(t));
        }
        assert!("zigzag".parse::<TraversalChoice>().is_err());
    }

    #[test]
    fn spp_must_be_a_power_of_two_in_range() {
        let o = |spp| StochasticOptions {
            spp: Some(spp),
            ..Default::default()
        };
        assert_eq!(StochasticOptions::default().spp().ok(), Some(DEFAULT_SPP));
        assert_eq!(o(64).spp().ok(), Some(64));
        for bad in [0, 3, 12, 2 * MAX_SPP] {
            assert!(o(bad).spp().is_err(), "{bad}");
        }
    }

    #[test]
    fn passes_split_only_what_does_not_fit() {
        // The compare scenes at 1024 spp: 640 x 360 (640 x 368 in whole bins) needs two
        // passes, 512 x 256 fits exactly.
        assert_eq!(passes(640, 360, 1024, MAX_SAMPLES).ok(), Some(2));
        assert_eq!(passes(512, 256, 1024, MAX_SAMPLES).ok(), Some(1));
        assert_eq!(passes(640, 360, 256, MAX_SAMPLES).ok(), Some(1));
        // The count is what raster-hier allocates.
        for (w, h, spp) in [(1u32, 1u32, 1u32), (17, 17, 4), (640, 360, 2), (4096, 1, 8)] {
            let b = SampleBuffer::<f64>::new(w, h, spp, TILE, BIN, ZMAX_SLICES, 0).unwrap();
            let held = buffer_pixels(w, h) * u64::from(spp);
            assert_eq!(b.depths().len() as u64, held, "{w}x{h}x{spp}");
            assert_eq!(b.ids().len() as u64, held, "{w}x{h}x{spp}");
        }
        // Exhaustively on small limits: the smallest power of two that fits.
        for limit in 1..=600u64 {
            for (w, h) in [(1u32, 1u32), (3, 5), (16, 16), (7, 20)] {
                let px = u64::from(w.div_ceil(16) * 16 * h.div_ceil(16) * 16);
                for spp in (0..=10).map(|k| 1u32 << k) {
                    match passes(w, h, spp, limit) {
                        Ok(p) => {
                            assert!(p.is_power_of_two() && p <= spp);
                            assert!(px * u64::from(spp / p) <= limit);
                            assert!(p == 1 || px * u64::from(spp / (p / 2)) > limit);
                        }
                        Err(e) => {
                            assert!(px > limit, "{w}x{h} {spp} {limit}");
                            assert!(e.to_string().contains("`max_pass_samples`"), "{e}");
                        }
                    }
                }
            }
        }
    }
}
