//! The payloads intervals carry and the shaders the resolve applies to them: flat
//! materials an [`Rgba`] colour (straight alpha), textured materials a [`Textured`] payload
//! (UV at the interval ends from perspective-correct barycentrics, Gribel 2010 Eq. 11-12)
//! shaded by [`PreparedScene::shade`] through a tap filter with the number of taps adapted
//! to the partition (`AdaptiveTaps`).
//!
//! `with_payloads` picks the pair for a scene, so every user of the chain (a render, the
//! pixel visualiser, ewa's surface intervals) makes and shades payloads the same way.

use glam::DVec2;
use interval_buffer::{Interval, Payload, Rgba, Textured};
use resolve::{Flat, Shader, TapFilter};

use super::end_samples::{EndSamples, SampleKey};
use super::lit::{LitShader, lit_payloads};
use super::{Real, cf};
use crate::lighting::ShadingSamples;
use crate::prepared::PreparedScene;
use crate::texture::{Texture, ceil};

/// Texture taps per texel of a partition's UV segment: a textured span's filter takes this
/// many taps per texel its UV segment crosses.
pub const TAPS_PER_TEXEL: f64 = 16.0;

/// Most texture taps per partition for textured payloads (the cap on the per-texel count).
pub const TEXTURE_TAPS: usize = 256;

/// Makes payloads from (material, uv at span start, uv at span end).
pub(crate) trait MakePayload<F: Real = f32>: Sync {
    /// The payload type.
    type P: Payload<F> + Copy + Default + Send + Sync;
    /// Texels per unit of UV of `material`'s texture, or `None` when its payload carries
    /// no UV (then moving spans are never cut into pieces; see
    /// [`super::pieces::pieces_within`]).
    fn texels(&self, material: u32) -> Option<DVec2> {
        let _ = material;
        None
    }
    /// For payloads that carry barycentrics: the resolution (cells per unit of barycentric
    /// weight) at which a span's barycentric path must stay straight, as
    /// [`MakePayload::texels`] for UVs; `None` when the payload's colour does not follow
    /// them.
    fn bary_cells(&self, material: u32) -> Option<f64> {
        let _ = material;
        None
    }
    /// The payload of a span of `material` with UV `uv0` at its start and `uv1` at its end.
    fn make(&self, material: u32, uv0: DVec2, uv1: DVec2) -> Self::P;
    /// The payload of a span of triangle `tri` (of `material`) with UVs `uv` and barycentric
    /// weights `bary` at its start and end; payloads that need no more than the UVs take
    /// [`MakePayload::make`].
    fn make_at(&self, tri: u32, material: u32, uv: [DVec2; 2], bary: [[f64; 3]; 2]) -> Self::P {
        let _ = (tri, bary);
        self.make(material, uv[0], uv[1])
    }
}

/// Flat payloads: the material's straight-alpha colour.
pub(crate) struct FlatPayload<F = f32>(pub Vec<Rgba<F>>);

impl<F: Real> MakePayload<F> for FlatPayload<F> {
    type P = Rgba<F>;
    fn make(&self, material: u32, _: DVec2, _: DVec2) -> Rgba<F> {
        self.0.get(material as usize).copied().unwrap_or_default()
    }
}

/// Textured payloads: UVs at the ends and the material's alpha; per material the size of
/// its texture in texels, if it has one (only those spans are cut into pieces).
pub(crate) struct TexPayload<F = f32>(pub Vec<F>, pub Vec<Option<DVec2>>);

impl<F: Real> MakePayload<F> for TexPayload<F> {
    type P = Textured<F>;
    fn texels(&self, material: u32) -> Option<DVec2> {
        self.1.get(material as usize).copied().flatten()
    }
    fn make(&self, material: u32, uv0: DVec2, uv1: DVec2) -> Textured<F> {
        Textured {
            uv_start: [cf(uv0.x), cf(uv0.y)],
            uv_end: [cf(uv1.x), cf(uv1.y)],
            material,
            alpha: self
                .0
                .get(material as usize)
                .copied()
                .unwrap_or_else(F::zero),
        }
    }
}

/// Straight-alpha colour from premultiplied `p`, alpha divided by `material_alpha`.
fn straight<F: Real>(p: [f64; 4], material_alpha: f64) -> Rgba<F> {
    if p[3] <= 0.0 || material_alpha <= 0.0 {
        return Rgba::default();
    }
    let a = p[3];
    // An opaque texel of an opaque material: the divisions below are by one (exact), so
    // skip them; the same bits, four divisions fewer per texture tap.
    if a == 1.0 && material_alpha == 1.0 {
        return Rgba::new(cf(p[0]), cf(p[1]), cf(p[2]), F::one());
    }
    Rgba::new(
        cf(p[0] / a),
        cf(p[1] / a),
        cf(p[2] / a),
        cf((a / material_alpha).min(1.0)),
    )
}

/// Flat payload table: each material's straight-alpha colour.
pub(crate) fn flat_payloads<F: Real>(scene: &PreparedScene) -> FlatPayload<F> {
    FlatPayload(
        scene
            .materials
            .iter()
            .map(|m| {
                let c = m.color.map(cf::<F>);
                Rgba::new(c[0], c[1], c[2], c[3].max(F::zero()).min(F::one()))
            })
            .collect(),
    )
}

/// Material alphas and texture sizes for textured payloads.
pub(crate) fn tex_payloads<F: Real>(scene: &PreparedScene) -> TexPayload<F> {
    TexPayload(
        scene
            .materials
            .iter()
            .map(|m| cf(m.color[3].clamp(0.0, 1.0)))
            .collect(),
        scene
            .materials
            .iter()
            .map(|m| {
                let t = scene.texture_of(m)?;
                Some(DVec2::new(f64::from(t.width()), f64::from(t.height())))
            })
            .collect(),
    )
}

/// The texture lookup handed to the resolve: [`PreparedScene::shade`] divided by the
/// material alpha the payload already carries (the filters multiply it back).
pub(crate) struct SceneTexture<'a>(pub &'a PreparedScene);

impl SceneTexture<'_> {
    /// The premultiplied colour of `material` at `uv` and the material's alpha.
    fn shade<F: Real>(&self, m: u32, uv: [F; 2]) -> ([f64; 4], f64) {
        let a = self.0.materials.get(m as usize).map_or(0.0, |m| m.color[3]);
        (self.0.shade(m, uv_f64(uv)), a)
    }
}

/// A UV pair as f64.
fn uv_f64<F: Real>(uv: [F; 2]) -> DVec2 {
    let [u, v] = uv.map(|c| c.to_f64().unwrap_or(0.0));
    DVec2::new(u, v)
}

impl<F: Real> resolve::Texture<F> for SceneTexture<'_> {
    fn sample(&self, m: u32, uv: [F; 2]) -> Rgba<F> {
        let (p, a) = self.shade(m, uv);
        straight(p, a)
    }

    fn sample_premultiplied(&self, m: u32, uv: [F; 2]) -> [F; 4] {
        let (p, a) = self.shade(m, uv);
        premultiplied(p, a).map(cf)
    }
}

/// [`straight`] premultiplied again, without the round trip: `p / a` (zero where `p` or
/// `a` has no alpha; alpha at most 1).
fn premultiplied(p: [f64; 4], a: f64) -> [f64; 4] {
    if p[3] <= 0.0 || a <= 0.0 {
        return [0.0; 4];
    }
    if a == 1.0 && p[3] <= 1.0 {
        return p;
    }
    // Alpha above one after the division is clamped as `straight` clamps it.
    let s = if p[3] / a > 1.0 { 1.0 / p[3] } else { 1.0 / a };
    p.map(|c| c * s)
}

/// Textured shading with the number of taps adapted to the partition: the tap filter of
/// the resolve crate ([`TapFilter`], midpoint rule along the partition's UV segment, each
/// tap weighted by the shutter response) with `clamp(ceil(TAPS_PER_TEXEL L), 1,
/// TEXTURE_TAPS)` taps, where L is the segment's length in texels, so taps stay at most
/// 1/16 texel apart. Inside one bilinear cell the texture is a quadratic in the step, which
/// the midpoint rule integrates with error below 1/24 of its second difference; where the
/// segment crosses a cell border the bilinear texture has a kink, and the midpoint rule's
/// error there grows with the square of the spacing (two taps per texel left an RMSE of
/// 1.3e-3 on the scrolling checker backdrop of `pills` once its spans stopped being cut
/// into 1/32-shutter pieces; 16 per texel, 8e-5). A moving mesh whose spans each cover a
/// small fraction of a texel (clothball) still costs one lookup per partition.
///
/// Where the segment crosses no more texel cells than it would take taps, it is integrated
/// exactly instead ([`crate::texture::Texture::segment_average`]: one Simpson step per cell
/// with the cell's texels fetched once), which is both cheaper and free of the midpoint
/// rule's error.
pub(crate) struct AdaptiveTaps<'a> {
    texture: &'a SceneTexture<'a>,
    /// Per material, its texture looked up once.
    materials: Vec<MaterialTexture<'a>>,
    /// This shader's part of the keys of the taps it remembers ([`EndSamples`]).
    id: u64,
}

impl<'a> AdaptiveTaps<'a> {
    pub(crate) fn new(texture: &'a SceneTexture<'a>) -> Self {
        let scene = texture.0;
        let materials = scene
            .materials
            .iter()
            .enumerate()
            .map(|(i, m)| match scene.texture_of(m) {
                Some(t) => MaterialTexture::Textured {
                    texels: texel_scale(Some(t)),
                    texture: t,
                    colour: m.color,
                },
                None => {
                    let (p, a) = texture.shade(i as u32, [0.0, 0.0]);
                    MaterialTexture::Uniform(premultiplied(p, a))
                }
            })
            .collect();
        AdaptiveTaps {
            texture,
            materials,
            id: EndSamples::shader_id(),
        }
    }

    /// The premultiplied texture tap of `material` at `uv` ([`SceneTexture`]'s lookup),
    /// remembered by this thread for the partitions that take the same tap again.
    fn remembered_tap<F: Real>(&self, material: u32, uv: [F; 2]) -> [F; 4] {
        let key = SampleKey::tap(self.id, material, uv_f64(uv).to_array());
        if let Some(c) = EndSamples::find(&key) {
            return c.map(cf);
        }
        let c: [F; 4] = resolve::Texture::sample_premultiplied(self.texture, material, uv);
        // Exact: every value of F is one of f64.
        EndSamples::keep(&key, c.map(|v| v.to_f64().unwrap_or(f64::NAN)));
        c
    }
}

/// A material as [`AdaptiveTaps`] shades it.
enum MaterialTexture<'a> {
    /// Untextured: its colour does not depend on UV. The premultiplied lookup of
    /// [`SceneTexture`] at any UV, made once.
    Uniform([f64; 4]),
    /// Textured: the scale of its tap count and what its exact segment integral needs.
    Textured {
        /// The larger texture dimension in texels.
        texels: f64,
        /// The texture.
        texture: &'a Texture,
        /// The material's straight-alpha colour.
        colour: [f64; 4],
    },
}

impl MaterialTexture<'_> {
    /// The exact weighted mean of the material's colour along the UV segment `uv0` → `uv1`
    /// ([`Texture::segment_average`] times the material's colour), divided by the material
    /// alpha as [`resolve::Texture::sample_premultiplied`] is; `None` when the material
    /// has no texture or the exact integral takes more pieces than `taps` point taps (a
    /// whole number, as [`tap_steps`] gives it).
    #[inline]
    fn exact_if_cheaper<F: Real>(
        &self,
        [uv0, uv1]: [[F; 2]; 2],
        [w0, w1]: [F; 2],
        taps: f64,
    ) -> Option<[F; 4]> {
        // By reference: the colour is read after the integral, not copied across the call.
        let MaterialTexture::Textured {
            texture, colour: c, ..
        } = self
        else {
            return None;
        };
        if c[3] <= 0.0 {
            return Some([F::zero(); 4]);
        }
        let w = [w0.to_f64()?, w1.to_f64()?];
        let t = texture.segment_average_within(uv_f64(uv0), uv_f64(uv1), w, taps - 1.0)?;
        // The premultiplied base colour divided by its alpha is the straight colour.
        Some([cf(c[0] * t[0]), cf(c[1] * t[1]), cf(c[2] * t[2]), cf(t[3])])
    }
}

/// The larger dimension in texels of `texture` (0 for none): the scale of [`tap_count`].
fn texel_scale(texture: Option<&Texture>) -> f64 {
    texture.map_or(0.0, |t| f64::from(t.width().max(t.height())))
}

/// `clamp(ceil(TAPS_PER_TEXEL L), 1, TEXTURE_TAPS)` for the UV step `(du, dv)` on a texture
/// of `texels` texels (its larger dimension; 0 gives 1 tap), L = max(|du|, |dv|) texels;
/// [`TEXTURE_TAPS`] when L is not finite.
fn tap_count<F: Real>(texels: f64, du: F, dv: F) -> usize {
    tap_steps(texels, du, dv) as usize
}

/// [`tap_count`] as the float it is computed in (an integer in 1..=[`TEXTURE_TAPS`]): the
/// shading hot path compares it and hands it on as a float, without the round trip through
/// an integer.
#[inline]
fn tap_steps<F: Real>(texels: f64, du: F, dv: F) -> f64 {
    let len = du.abs().max(dv.abs()).to_f64().unwrap_or(f64::INFINITY) * texels;
    if len.is_finite() {
        ceil(TAPS_PER_TEXEL * len).clamp(1.0, TEXTURE_TAPS as f64)
    } else {
        TEXTURE_TAPS as f64
    }
}

/// How many texture taps a partition's UV step takes: `clamp(ceil(TAPS_PER_TEXEL L), 1,
/// TEXTURE_TAPS)` with L the step's length in texels (see [`AdaptiveTaps`]).
pub(crate) struct TapCount {
    /// Per material: the larger texture dimension in texels (0 for untextured).
    texels: Vec<f64>,
}

impl TapCount {
    pub(crate) fn new(scene: &PreparedScene) -> Self {
        let texels = scene
            .materials
            .iter()
            .map(|m| texel_scale(scene.texture_of(m)))
            .collect();
        TapCount { texels }
    }

    /// Taps for the UV step `(du, dv)` of `material` (1 when it has no texture).
    pub(crate) fn taps<F: Real>(&self, material: u32, du: F, dv: F) -> usize {
        let n = self.texels.get(material as usize).copied().unwrap_or(0.0);
        tap_count(n, du, dv)
    }
}

impl<F: Real> Shader<F, Textured<F>> for AdaptiveTaps<'_> {
    fn shade(&self, iv: &Interval<F, Textured<F>>, t0: F, t1: F, w0: F, w1: F) -> [F; 4] {
        let p = &iv.payload;
        let material = self.materials.get(p.material as usize);
        let texels = match material {
            // Untextured: the colour does not depend on UV, so the one tap needs neither UV
            // nor a lookup.
            Some(MaterialTexture::Uniform(c)) => {
                return resolve::uniform_colour(c.map(cf), p.alpha, w0, w1);
            }
            Some(MaterialTexture::Textured { texels, .. }) => *texels,
            None => 0.0,
        };
        if texels == 0.0 {
            let origin = [F::zero(); 2];
            // A material index out of range (or a texture without texels): the scene's
            // lookup.
            return TapFilter::new(self.texture, 1).shade_segment(
                (p.material, p.alpha),
                origin,
                origin,
                w0,
                w1,
            );
        }
        let ([u0, v0], [u1, v1]) = (p.uv_start, p.uv_end);
        if u0 == u1 && v0 == v1 {
            // A static surface: its UV segment is a point in every partition, which takes
            // one tap there (what the tap filter below computes for it, to the bit). A
            // backdrop seen between moving objects takes the same tap in many partitions.
            let half = cf::<F>(0.5);
            let uv = [u0 + (u1 - u0) * half, v0 + (v1 - v0) * half];
            return resolve::uniform_colour(self.remembered_tap(p.material, uv), p.alpha, w0, w1);
        }
        let (uv0, uv1) = (resolve::uv_at(iv, t0), resolve::uv_at(iv, t1));
        let taps = tap_steps(texels, uv1[0] - uv0[0], uv1[1] - uv0[1]);
        // The exact segment integral where it takes no more texture cells than taps.
        if taps > 1.0
            && let Some(c) = material.and_then(|m| m.exact_if_cheaper([uv0, uv1], [w0, w1], taps))
        {
            return c.map(|c| c * p.alpha);
        }
        // The UV ends computed once for the tap count and the filter (what
        // `TapFilter::shade` would compute again from the interval).
        TapFilter::new(self.texture, taps as usize).shade_segment(
            (p.material, p.alpha),
            uv0,
            uv1,
            w0,
            w1,
        )
    }

    fn shade_at(&self, iv: &Interval<F, Textured<F>>, t: F) -> [F; 4] {
        TapFilter::new(self.texture, 1).shade_at(iv, t)
    }
}

/// A computation over the chain that is generic in the payload kind: handed the payload
/// maker and the shader [`with_payloads`] picks for the scene.
pub(crate) trait WithPayloads<F: Real> {
    /// What it computes.
    type Output;
    /// Runs it with payloads made by `mk` and shaded by `shader`.
    fn run<M: MakePayload<F>, S: Shader<F, M::P> + Sync>(self, mk: &M, shader: &S) -> Self::Output;
}

/// Runs `job` with the scene's payloads: [`super::lit::Lit`] ones shaded by
/// [`LitShader`] with `shading` samples when the scene has lit materials, else textured ones shaded by [`AdaptiveTaps`] over
/// [`SceneTexture`] when `textures` (the pipeline has textured materials), else flat
/// colours shaded by [`Flat`].
pub(crate) fn with_payloads<F: Real, W: WithPayloads<F>>(
    scene: &PreparedScene,
    textures: bool,
    shading: ShadingSamples,
    job: W,
) -> W::Output {
    if scene.any_lit() {
        job.run(&lit_payloads::<F>(scene), &LitShader::new(scene, shading))
    } else if textures {
        let tex = SceneTexture(scene);
        job.run(&tex_payloads::<F>(scene), &AdaptiveTaps::new(&tex))
    } else {
        job.run(&flat_payloads::<F>(scene), &Flat)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fewest taps at most 1/[`TAPS_PER_TEXEL`] texel apart over a step of `len`
    /// texels, found by counting up, within 1..=[`TEXTURE_TAPS`].
    fn fewest(len: f64) -> usize {
        (1..=TEXTURE_TAPS)
            .find(|&n| n as f64 >= TAPS_PER_TEXEL * len)
            .unwrap_or(TEXTURE_TAPS)
    }

    #[test]
    fn tap_counts_are_the_fewest_that_keep_taps_a_sixteenth_of_a_texel_apart() {
        let texels = 64.0;
        for k in [
            0.0,
            0.5,
            1.0,
            1.0 + 1e-9,
            2.0,
            2.5,
            16.0,
            255.9,
            256.0,
            257.0,
            1e9,
        ] {
            // A step of k / 16 texels, in either direction along u or v.
            let d = k / (TAPS_PER_TEXEL * texels);
            let want = fewest(k / TAPS_PER_TEXEL);
            assert_eq!(tap_count(texels, d, 0.0), want, "{k}");
            assert_eq!(tap_count(texels, 0.0, -d), want, "{k}");
        }
        assert_eq!(tap_count(0.0, 3.0, 3.0), 1, "untextured");
        // A NaN step (f64::max passes over one NaN operand, not two).
        assert_eq!(tap_count(texels, f64::NAN, f64::NAN), TEXTURE_TAPS);
        assert_eq!(tap_count(texels, f64::INFINITY, 0.0), TEXTURE_TAPS);
    }
}
