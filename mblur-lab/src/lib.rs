//! # mblur-lab
//!
//! The lab tools around the [`mblur`] renderer: [`compare::compare`] renders a reference and
//! a ladder of settings per method and reports wall time, peak heap and error
//! ([`metrics`]: PSNR, RMSE, max abs, SSIM) as a table, CSV, Markdown ([`report`]) and an
//! error-vs-time plot ([`plot`]), with the [`pareto`] check (does an analytic run match every
//! good accum or stochastic run in PSNR at no more time?); [`inspect`] draws one pixel's time
//! intervals as SVG.

pub mod compare;
pub mod inspect;
pub mod metrics;
pub mod pareto;
pub mod plot;
pub mod record;
pub mod report;
pub mod threads;
