//! # tmsnet
//!
//! Time-ordered (0,m,3)-net sampler with Larcher-Pillichshammer spatial projection.
//!
//! Implements Munkberg, Clarberg, Hasselgren, Toth, Sugihara and Akenine-Möller 2011,
//! "Hierarchical Stochastic Motion Blur Rasterization", §5 and Appendix A: the permuted
//! generator matrices (Eq. 10-12, 17, 19) whose point j has time j / 2^m, so the samples of a
//! time range are a contiguous index range, with random digit scrambling per tile.
//!
//! **Status: not implemented yet** (issue 5 builds it). The planned entry point is the paper's
//! GetXY, `get_xy(j, m)`.
