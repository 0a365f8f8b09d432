//! # integration-tests
//!
//! End-to-end tests of the `mblur` renderer at small resolutions, each against an independent
//! reference (accumulation of many static renders) rather than against the method itself.
//! The tests live in `tests/`; this library is intentionally empty.
//!
//! **Status: not implemented yet** (issue 11 adds the tests once the renderer exists).
