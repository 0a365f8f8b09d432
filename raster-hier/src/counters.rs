//! Per-frame cost counters, like the statistics of Munkberg 2011, §8 (Table 2).

use core::ops::AddAssign;

/// Arithmetic cost estimates (floating-point operations, a MADD counted as one) of the unit
/// operations, used for [`Counters::arithmetic`]. They follow the operation counts of the
/// formulas as implemented here; they are estimates, not measurements.
pub mod cost {
    /// Triangle setup: edge-eqn's three moving edges (6 cross products), the orientation
    /// Bernstein form (8 determinants), frustum interval (5 planes × 3 vertices) and bound.
    pub const SETUP: u64 = 180;
    /// Extra setup of the linearised test's γ over a region (3 edges × 4 corners × 2 dots).
    pub const LINEARISE: u64 = 36;
    /// Moving AABB vs four tile planes (Eq. 1-2): 2 dots + a division per plane.
    pub const BOX_TEST: u64 = 16;
    /// Linearised moving-edge test (Eq. 8-9) per edge and winding: 2 MADD + a division.
    pub const LINEAR_EDGE: u64 = 3;
    /// Window-linearised edge test (per tile and level), per edge: coefficients at t₀
    /// (3 Horner), two slope vectors (6 MADD) and the rounding margin (3 abs-dots).
    pub const WINDOW_EDGE_SETUP: u64 = 21;
    /// Window-linearised edge test per edge and winding: 3 n-corner dots, a min, a division.
    pub const WINDOW_EDGE: u64 = 8;
    /// Exact edge test per edge, corner and winding: 3 dots and a quadratic solve.
    pub const EXACT_EDGE_CORNER: u64 = 18;
    /// CONVEX: one hull edge against a tile (2 MADD + compare).
    pub const HULL_EDGE: u64 = 3;
    /// INTERLEAVE: per-time triangle setup (vertices at t, 3 edge coefficient sets, bbox).
    pub const TIME_SETUP: u64 = 40;
    /// INTERLEAVE: static tile test at one time (box 8 + 3 edges × 2).
    pub const STATIC_TILE: u64 = 14;
    /// Per-sample inside test at time t: 3 edges × (3 coefficient Horners of 2 MADD + a dot).
    pub const SAMPLE_TEST: u64 = 27;
    /// Depth at a covered sample (rational depth, edge-eqn Eq. 15) and compare.
    pub const DEPTH_TEST: u64 = 30;
    /// z-max query for a tile over a time range.
    pub const ZMAX_QUERY: u64 = 4;
    /// Levels finer than the sample-pattern tile: finding one pixel's samples in a time
    /// range (two binary searches over its time-sorted samples, ≈ 2 log2 16 compares).
    pub const PIXEL_RANGE: u64 = 8;
}

/// What one frame (or part of it) cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counters {
    /// Triangles handed to the rasteriser.
    pub triangles_in: u64,
    /// Triangles removed by temporal view-frustum culling (or invalid input).
    pub frustum_culled: u64,
    /// Triangles removed by motion back-face culling.
    pub backface_culled: u64,
    /// Triangles set up for traversal.
    pub triangles_set_up: u64,
    /// Triangles that took the INTERLEAVE fallback (§7 heuristic).
    pub fallbacks: u64,
    /// Tile tests performed (any level, any kind).
    pub tile_tests: u64,
    /// Sample (inside) tests.
    pub sample_tests: u64,
    /// Depth tests (covered samples).
    pub depth_tests: u64,
    /// Samples written (passed LESS_EQUAL).
    pub samples_written: u64,
    /// Finest tiles (pattern tiles, or the quads / pixels of levels below them) skipped by
    /// the time-dependent z-max test.
    pub zmax_culls: u64,
    /// Arithmetic estimate, in operations (see [`cost`]).
    pub arithmetic: u64,
}

impl AddAssign for Counters {
    fn add_assign(&mut self, o: Self) {
        self.triangles_in += o.triangles_in;
        self.frustum_culled += o.frustum_culled;
        self.backface_culled += o.backface_culled;
        self.triangles_set_up += o.triangles_set_up;
        self.fallbacks += o.fallbacks;
        self.tile_tests += o.tile_tests;
        self.sample_tests += o.sample_tests;
        self.depth_tests += o.depth_tests;
        self.samples_written += o.samples_written;
        self.zmax_culls += o.zmax_culls;
        self.arithmetic += o.arithmetic;
    }
}
