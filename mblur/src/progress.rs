//! Progress reporting from renderers, independent of any terminal library (the `mblur`
//! binary implements it with indicatif).

/// Receives progress from a render. Must be cheap and thread-safe.
pub trait Progress: Sync {
    /// A render of `total` steps starts; `unit` names a step in the plural (`sub-frames`,
    /// `rows`, `bands`, `stages`).
    fn start(&self, total: u64, unit: &'static str);
    /// `steps` more steps are done.
    fn advance(&self, steps: u64);
    /// The render is done.
    fn finish(&self);
}

/// Ignores progress.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoProgress;

impl Progress for NoProgress {
    fn start(&self, _total: u64, _unit: &'static str) {}
    fn advance(&self, _steps: u64) {}
    fn finish(&self) {}
}
