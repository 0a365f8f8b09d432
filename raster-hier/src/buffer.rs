//! The multisampled depth / payload buffer with a time-dependent z-max per tile
//! (Munkberg 2011, §7 "Time-Dependent Occlusion Culling"), and the box-filter resolve.

use num_traits::Float;
use tmsnet::{Scramble, TileLayout, TileSampler, TimeOrderedNet};

use crate::error::Error;

/// The payload of a sample that no triangle covered.
pub const NO_HIT: u32 = u32::MAX;

/// Where a sample lies inside its pixel. Either way a pixel's S samples keep the net's
/// times, one in each of the S strata `[k / S, (k + 1) / S)` of the shutter (the pixel is an
/// elementary box of the tile's (0, m, 3)-net, Munkberg 2011 §5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Footprint {
    /// At tmsnet's sub-pixel position (Munkberg 2011's setting): the box-filter resolve
    /// integrates over pixel area and shutter, so static edges are antialiased.
    #[default]
    Area,
    /// At the pixel centre: the resolve integrates over the shutter only, the quantity a
    /// renderer that point-samples pixel centres over time computes. Compare against such a
    /// reference with this footprint; with [`Footprint::Area`] the error stops falling at
    /// the spatial-filter difference however many samples are taken.
    Centre,
}

impl Footprint {
    /// Both footprints, in the order [`Footprint::name`] lists them.
    pub const ALL: [Footprint; 2] = [Footprint::Area, Footprint::Centre];

    /// The name [`str::parse`] accepts: `area` or `centre`.
    pub fn name(self) -> &'static str {
        match self {
            Footprint::Area => "area",
            Footprint::Centre => "centre",
        }
    }
}

impl core::fmt::Display for Footprint {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

impl core::str::FromStr for Footprint {
    type Err = String;

    /// `area` or `centre` (`center` is accepted too).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "area" => Ok(Footprint::Area),
            "centre" | "center" => Ok(Footprint::Centre),
            _ => Err(format!("unknown footprint `{s}` (expected area or centre)")),
        }
    }
}

/// A W x H image with S samples per pixel: per sample a depth (`F`, +∞ when empty) and a
/// payload id (`u32`, [`NO_HIT`] when empty), plus per finest tile a z-max for each of
/// `zmax_slices` consecutive groups of sample times (a tz-slice buffer).
///
/// Samples come from tmsnet: the image is cut into `tile` x `tile` pixel tiles, each with
/// its own scrambled time-ordered net of `tile² · S` points (index j has time j / 2^m).
/// Storage is bin-major so that one coarsest-level bin (`bin` x `bin` pixels) owns one
/// contiguous slice: bin, then tile within the bin (row-major), then net index j. That is
/// what lets [`crate::rasterise`] process bins in parallel without sharing memory.
#[derive(Clone, Debug)]
pub struct SampleBuffer<F> {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) spp: u32,
    pub(crate) tile: u32,
    pub(crate) bin: u32,
    pub(crate) bins_x: u32,
    pub(crate) bins_y: u32,
    pub(crate) zslices: u32,
    pub(crate) layout: TileLayout,
    pub(crate) net: TimeOrderedNet,
    pub(crate) seed: u64,
    pub(crate) footprint: Footprint,
    pub(crate) depth: Vec<F>,
    pub(crate) id: Vec<u32>,
    pub(crate) zmax: Vec<F>,
}

impl<F: Float> SampleBuffer<F> {
    /// A cleared buffer. `tile` (finest traversal level and sample-pattern tile) and `bin`
    /// (coarsest level) are powers of two with `tile <= bin <= 4096`; the image is at most
    /// 2^20 pixels on a side; `spp` is a power of two;
    /// `zmax_slices` a power of two dividing `tile² · spp`. `seed` scrambles the pattern.
    pub fn new(
        width: u32,
        height: u32,
        spp: u32,
        tile: u32,
        bin: u32,
        zmax_slices: u32,
        seed: u64,
    ) -> Result<Self, Error> {
        if width == 0 || height == 0 || width > 1 << 20 || height > 1 << 20 {
            return Err(Error::InvalidConfig("image size must be in 1..=2^20"));
        }
        if !(tile.is_power_of_two() && bin.is_power_of_two() && tile <= bin && bin <= 1 << 12) {
            return Err(Error::InvalidConfig(
                "tile and bin must be powers of two, tile <= bin",
            ));
        }
        let layout = TileLayout::new(tile, tile, spp)?;
        let n = layout.samples();
        if !(zmax_slices.is_power_of_two() && zmax_slices <= n) {
            return Err(Error::InvalidConfig(
                "zmax_slices must be a power of two <= tile² · spp",
            ));
        }
        let net = TimeOrderedNet::permuted(layout.m())?;
        let bins_x = width.div_ceil(bin);
        let bins_y = height.div_ceil(bin);
        let tiles_per_bin = (bin / tile) * (bin / tile);
        let nbins = u64::from(bins_x) * u64::from(bins_y);
        let total = nbins * u64::from(tiles_per_bin) * u64::from(n);
        if total > (1u64 << 34) {
            return Err(Error::InvalidConfig("sample buffer too large"));
        }
        let total =
            usize::try_from(total).map_err(|_| Error::InvalidConfig("sample buffer too large"))?;
        let ztotal = total / n as usize * zmax_slices as usize;
        Ok(SampleBuffer {
            width,
            height,
            spp,
            tile,
            bin,
            bins_x,
            bins_y,
            zslices: zmax_slices,
            layout,
            net,
            seed,
            footprint: Footprint::Area,
            depth: vec![F::infinity(); total],
            id: vec![NO_HIT; total],
            zmax: vec![F::infinity(); ztotal],
        })
    }

    /// The same buffer with its samples placed by `footprint` (a new buffer is
    /// [`Footprint::Area`]). Set it before rasterising: the samples already written were
    /// tested at the old positions.
    pub fn with_footprint(mut self, footprint: Footprint) -> Self {
        self.footprint = footprint;
        self
    }

    /// Where the samples lie inside their pixels.
    pub fn footprint(&self) -> Footprint {
        self.footprint
    }

    /// Resets every sample to empty (depth +∞, [`NO_HIT`]) and every z-max to +∞.
    pub fn clear(&mut self) {
        self.depth.fill(F::infinity());
        self.id.fill(NO_HIT);
        self.zmax.fill(F::infinity());
    }

    /// Image width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Image height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Samples per pixel.
    pub fn spp(&self) -> u32 {
        self.spp
    }

    /// Finest tile size (the sample-pattern tile).
    pub fn tile(&self) -> u32 {
        self.tile
    }

    /// Coarsest tile size (the bin that one thread owns).
    pub fn bin(&self) -> u32 {
        self.bin
    }

    /// Samples per finest tile, `tile² · spp` = 2^m.
    pub fn samples_per_tile(&self) -> u32 {
        self.layout.samples()
    }

    /// Every sample's depth, in storage order (bin, tile, net index).
    pub fn depths(&self) -> &[F] {
        &self.depth
    }

    /// Every sample's payload id, in storage order.
    pub fn ids(&self) -> &[u32] {
        &self.id
    }

    /// The tmsnet sampler of finest tile `(tx, ty)` (in tile units): the permuted net
    /// scrambled with the tile's hash, as `TileSampler::new` builds it.
    /// `None` cannot happen for a buffer built by [`SampleBuffer::new`] (net and layout
    /// are made together).
    pub fn sampler(&self, tx: u32, ty: u32) -> Option<TileSampler> {
        TileSampler::with_net(self.layout, self.net, Scramble::for_tile(tx, ty, self.seed)).ok()
    }

    /// Storage offset of sample j of finest tile `(tx, ty)`.
    pub fn offset(&self, tx: u32, ty: u32, j: u32) -> usize {
        let per_bin = self.bin / self.tile;
        let (bx, by) = (tx / per_bin, ty / per_bin);
        let (lx, ly) = (tx % per_bin, ty % per_bin);
        let bin = by as usize * self.bins_x as usize + bx as usize;
        let local = ly as usize * per_bin as usize + lx as usize;
        ((bin * (per_bin * per_bin) as usize) + local) * self.layout.samples() as usize + j as usize
    }

    /// Calls `f(px, py, x, y, t, depth, id)` for every sample inside the image: pixel,
    /// screen position (pixel units), time, depth and payload.
    pub fn for_each_sample(&self, mut f: impl FnMut(u32, u32, F, F, F, F, u32)) {
        let tiles_x = self.bins_x * (self.bin / self.tile);
        let tiles_y = self.bins_y * (self.bin / self.tile);
        for ty in 0..tiles_y {
            for tx in 0..tiles_x {
                let Some(sampler) = self.sampler(tx, ty) else {
                    continue;
                };
                let Ok(iter) = sampler.samples_in_indices::<F>(0..self.layout.samples()) else {
                    continue;
                };
                for s in iter {
                    let (px, py) = (tx * self.tile + s.pixel[0], ty * self.tile + s.pixel[1]);
                    if px >= self.width || py >= self.height {
                        continue;
                    }
                    let (x, y) = sample_xy(tx, ty, self.tile, self.footprint, &s);
                    let o = self.offset(tx, ty, s.index);
                    let (d, id) = (self.depth.get(o), self.id.get(o));
                    if let (Some(&d), Some(&id)) = (d, id) {
                        f(px, py, x, y, s.t, d, id);
                    }
                }
            }
        }
    }

    /// Box-filter resolve: each pixel's colour is the mean over its S samples of
    /// `colour(id)`, with `background` for samples no triangle covered. Row-major, W·H.
    pub fn resolve(&self, colour: impl Fn(u32) -> [f32; 4], background: [f32; 4]) -> Vec<[f32; 4]> {
        let mut out = vec![[0.0f32; 4]; self.width as usize * self.height as usize];
        let w = 1.0 / self.spp as f32;
        self.for_each_sample(|px, py, _, _, _, _, id| {
            let c = if id == NO_HIT { background } else { colour(id) };
            if let Some(o) = out.get_mut(py as usize * self.width as usize + px as usize) {
                for k in 0..4 {
                    o[k] += c[k] * w;
                }
            }
        });
        out
    }
}

/// Screen position (pixel units) of a tile sample: tile origin + pixel + sub-pixel offset
/// (tmsnet's, or one half for [`Footprint::Centre`]). Every traversal computes positions
/// with this one function, so all see the same bits.
#[inline]
pub(crate) fn sample_xy<F: Float>(
    tx: u32,
    ty: u32,
    tile: u32,
    footprint: Footprint,
    s: &tmsnet::TileSample<F>,
) -> (F, F) {
    let ox = F::from(f64::from(tx * tile + s.pixel[0])).unwrap_or_else(F::zero);
    let oy = F::from(f64::from(ty * tile + s.pixel[1])).unwrap_or_else(F::zero);
    match footprint {
        Footprint::Area => (ox + s.offset[0], oy + s.offset[1]),
        Footprint::Centre => {
            let half = F::from(0.5).unwrap_or_else(F::zero);
            (ox + half, oy + half)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pixel_gets_exactly_spp_samples() {
        let buf = SampleBuffer::<f32>::new(13, 7, 4, 4, 8, 4, 3).expect("valid");
        let mut count = vec![0u32; 13 * 7];
        buf.for_each_sample(|px, py, x, y, t, _, _| {
            assert!(x >= px as f32 && x < px as f32 + 1.0 && y >= py as f32 && y < py as f32 + 1.0);
            assert!((0.0..1.0).contains(&t));
            count[(py * 13 + px) as usize] += 1;
        });
        assert!(count.iter().all(|&c| c == 4));
        let img = buf.resolve(|_| [1.0; 4], [0.25, 0.5, 0.75, 1.0]);
        assert_eq!(img[0], [0.25, 0.5, 0.75, 1.0]);
    }

    /// Every pixel's samples, for each footprint and spp, against exhaustive enumeration:
    /// one time in each stratum [k / S, (k + 1) / S); at the centre for `Centre`, spread
    /// inside the pixel for `Area`; the same times for both.
    #[test]
    fn each_pixel_has_one_time_per_stratum_for_both_footprints() {
        let (w, h) = (13u32, 9u32);
        for spp in [1u32, 2, 4, 16, 64] {
            let mut times = Vec::new();
            for footprint in Footprint::ALL {
                let buf = SampleBuffer::<f64>::new(w, h, spp, 4, 8, 1, 5)
                    .expect("valid")
                    .with_footprint(footprint);
                assert_eq!(buf.footprint(), footprint);
                let mut strata = vec![vec![0u32; spp as usize]; (w * h) as usize];
                let mut spread = vec![(f64::INFINITY, f64::NEG_INFINITY); (w * h) as usize];
                let mut seen = Vec::new();
                buf.for_each_sample(|px, py, x, y, t, _, _| {
                    let p = (py * w + px) as usize;
                    strata[p][(t * f64::from(spp)) as usize] += 1;
                    let (cx, cy) = (x - f64::from(px), y - f64::from(py));
                    assert!((0.0..1.0).contains(&cx) && (0.0..1.0).contains(&cy));
                    if footprint == Footprint::Centre {
                        assert_eq!((cx, cy), (0.5, 0.5), "pixel ({px}, {py})");
                    }
                    spread[p] = (spread[p].0.min(cx), spread[p].1.max(cx));
                    seen.push((px, py, t.to_bits()));
                });
                assert!(strata.iter().flatten().all(|&c| c == 1), "spp {spp}");
                if footprint == Footprint::Area && spp >= 4 {
                    // Not all at one x: the net spreads a pixel's samples over its area.
                    assert!(spread.iter().all(|(lo, hi)| hi - lo > 0.2), "spp {spp}");
                }
                seen.sort_unstable();
                times.push(seen);
            }
            assert_eq!(times[0], times[1], "spp {spp}: footprints change the times");
        }
    }

    #[test]
    fn footprint_names_round_trip() {
        for f in Footprint::ALL {
            assert_eq!(f.name().parse::<Footprint>(), Ok(f));
            assert_eq!(f.to_string(), f.name());
        }
        assert_eq!("center".parse::<Footprint>(), Ok(Footprint::Centre));
        assert!(
            "middle"
                .parse::<Footprint>()
                .unwrap_err()
                .contains("area or centre")
        );
    }
}
