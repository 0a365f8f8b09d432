//! # raster-hier
//!
//! Hierarchical stochastic motion-blur rasterisation with tile temporal bounds.
//!
//! Implements Munkberg et al. 2011, "Hierarchical Stochastic Motion Blur Rasterization",
//! §3-§4 and §7: temporal frustum and back-face culling, the moving AABB vs tile planes test
//! (Eq. 1-2), the linearised moving-edge tile test (Eq. 4-9), 16/8/4 hierarchical traversal
//! feeding `tmsnet` samples to `edge-eqn` inside tests, and the BBOX, CONVEX and INTERLEAVE
//! baselines with cost counters.
//!
//! **Status: not implemented yet** (issue 9 builds it).
