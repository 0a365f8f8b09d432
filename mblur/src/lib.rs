//! # mblur
//!
//! The motion-blur renderer: reads a scene, analyses which effects it calls for (motion,
//! transparency, textures, interpenetration, splats) and composes the primitive crates
//! (`edge-eqn`, `bilinear-patch`, `interval-buffer`, `resolve`, `raster-hier` with `tmsnet`,
//! `ewa-splat`) into a pipeline that runs only those stages, producing PNG, EXR or PFM images.
//!
//! **Status: not implemented yet** (issue 10 builds the renderer and the `mblur` command).
