//! Textures as the resolve sees them: point lookups, and exact integrals along a segment.

use interval_buffer::Rgba;
use num_traits::Float;

/// A texture lookup (material, uv) → straight-alpha colour: the caller's shading function.
///
/// Any `Fn(u32, [F; 2]) -> Rgba<F>` is a texture, so a renderer can pass a closure that
/// looks up its material table and applies its own lighting.
pub trait Texture<F> {
    /// The straight-alpha colour of `material` at texture coordinates `uv`.
    fn sample(&self, material: u32, uv: [F; 2]) -> Rgba<F>;

    /// The premultiplied colour `[a r, a g, a b, a]` of [`Texture::sample`]; what the
    /// filters sum. A texture that holds premultiplied colour overrides it to skip the
    /// round trip through straight alpha.
    fn sample_premultiplied(&self, material: u32, uv: [F; 2]) -> [F; 4]
    where
        F: Float,
    {
        self.sample(material, uv).premultiplied()
    }
}

impl<F, G: Fn(u32, [F; 2]) -> Rgba<F>> Texture<F> for G {
    fn sample(&self, material: u32, uv: [F; 2]) -> Rgba<F> {
        self(material, uv)
    }
}

/// A texture that can integrate itself exactly along a straight UV segment (Rønnow 2021,
/// §4.3: "the continuous range of texels between the start and end UVs", which the paper
/// approximates with anisotropic filtering).
pub trait SegmentTexture<F>: Texture<F> {
    /// The premultiplied colour averaged along the segment `uv0` → `uv1` with a weight
    /// linear from `w0` at `uv0` to `w1` at `uv1`:
    /// ∫₀¹ (w0 + (w1 - w0) s) c(lerp(uv0, uv1, s)) ds / ((w0 + w1) / 2),
    /// where c is the premultiplied [`Texture::sample`]. `w0 = w1 = 0` means unweighted.
    fn segment_average(&self, material: u32, uv0: [F; 2], uv1: [F; 2], w0: F, w1: F) -> [F; 4];
}
