//! # resolve
//!
//! The temporal pixel resolve: turns a pixel's list of time intervals into its colour.
//!
//! Implements Gribel et al. 2010 §5.1 (the sweep over interval starts, ends and depth
//! crossings with a depth-sorted active list, integrated against the shutter response, Eq. 17)
//! and Rønnow et al. 2021 §4.3, Algorithm 1 (transparency, textured partitions with UV
//! interpolated per partition, optional intersection handling).
//!
//! **Status: not implemented yet** (issue 7 builds it). It consumes
//! [`interval_buffer::Interval`].
