//! # bilinear-patch
//!
//! Ray vs bilinear patch intersection and the space-time prism of a moving triangle.
//!
//! Implements Rønnow, Assarsson, Sintorn and Fratarcangeli 2021, "Fast Analytical Motion Blur
//! with Transparency", §3-§4.1: a moving triangle is a prism of two triangles and three
//! bilinear patches; a ray through a pixel centre hits it at up to eight points, which sorted
//! by time and paired give the coverage intervals. The ray/patch test follows Reshetov 2019,
//! "Cool Patches".
//!
//! **Status: not implemented yet** (issue 4 builds it). The planned entry points are
//! `Patch::new([q00, q10, q11, q01])`, `Patch::intersect(origin, dir, t_min, t_max)` and the
//! prism coverage of a pixel centre.
