//! Bands of image rows and the items (screen triangles, interval primitives) each band
//! holds: how the static path, the interval chain and ewa's surface intervals hand a
//! band's work to a thread without scanning every item of the frame.

/// Item indices per band of `rows` consecutive image rows, in item order.
#[derive(Debug, Clone, Default)]
pub(crate) struct Bins {
    bins: Vec<Vec<u32>>,
    rows: u32,
}

impl Bins {
    /// Bins items over an image `height` rows high in bands of `rows` rows (at least 1):
    /// `spans` yields, per item in index order, the first and last row it touches (both
    /// inside the image).
    pub(crate) fn new(height: u32, rows: u32, spans: impl IntoIterator<Item = (u32, u32)>) -> Self {
        let mut bins = Bins::default();
        bins.refill(height, rows, spans);
        bins
    }

    /// [`Bins::new`] into these bins, reusing their allocations (a frame's bins refilled
    /// for the next instant).
    pub(crate) fn refill(
        &mut self,
        height: u32,
        rows: u32,
        spans: impl IntoIterator<Item = (u32, u32)>,
    ) {
        let rows = rows.max(1);
        self.rows = rows;
        self.bins
            .resize_with(height.div_ceil(rows) as usize, Vec::new);
        for bin in &mut self.bins {
            bin.clear();
        }
        for (i, (y0, y1)) in spans.into_iter().enumerate() {
            for b in y0 / rows..=y1 / rows {
                let bin = self.bins.get_mut(b as usize);
                debug_assert!(bin.is_some(), "row {y1} of item {i} is below the image");
                if let Some(bin) = bin {
                    bin.push(i as u32);
                }
            }
        }
    }

    /// The items of the band holding row `y` (none below the image).
    pub(crate) fn band(&self, y: u32) -> &[u32] {
        self.bins
            .get((y / self.rows) as usize)
            .map_or(&[][..], |b| b.as_slice())
    }

    /// The items of every band, top to bottom.
    pub(crate) fn all(&self) -> &[Vec<u32>] {
        &self.bins
    }
}
