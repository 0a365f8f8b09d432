//! How `--method auto` (the default) picks a method for a scene, from what the scene is
//! made of and the [`Pipeline`] its effects call for:
//!
//! 1. splats only: `ewa` (Heinzle 2010), the only method that renders splats as splats;
//! 2. splats and triangles together: `accum` (it renders splats as discs), since `analytic`
//!    renders only triangles and `ewa` only splats; the reason is in the note;
//! 3. a fully static opaque triangle scene: `analytic`, which takes the static path for it
//!    (one static render, no interval storage at all);
//! 4. any other triangle scene: `analytic` (edge-eqn -> interval-buffer -> resolve, exact
//!    interval lists; Gribel 2010), which supports motion of objects and camera,
//!    transparency, textures, interpenetration and the near plane.

use crate::effects::Pipeline;
use crate::method::Method;
use crate::prepare::PreparedScene;

/// The method `auto` resolves to and why (printed by `mblur render`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct AutoChoice {
    /// The method that renders the scene (never [`Method::Auto`]).
    pub method: Method,
    /// One line saying why, starting with `method auto:`.
    pub note: String,
}

/// Picks the method for `scene` (see the module docs for the rules).
///
/// ```
/// use mblur::{Effects, Method, Scene};
/// let scene = Scene::builtin("splat-ball")?.prepare()?;
/// let choice = mblur::auto::choose(&scene, &Effects::analyse(&scene).pipeline());
/// assert_eq!(choice.method, Method::Ewa);
/// # Ok::<(), mblur::Error>(())
/// ```
pub fn choose(scene: &PreparedScene, pipeline: &Pipeline) -> AutoChoice {
    let (method, why) = if crate::ewa::applies(scene) {
        (Method::Ewa, "every object is a splat".to_string())
    } else if !scene.splats.is_empty() {
        (
            Method::Accum,
            format!(
                "the scene mixes {} triangles and {} splats; analytic renders only triangles and ewa only splats, accum renders both (splats as discs)",
                scene.triangles.len(),
                scene.splats.len()
            ),
        )
    } else if !pipeline.interval_storage {
        (
            Method::Analytic,
            "fully static opaque scene: the static path, no interval storage".to_string(),
        )
    } else {
        (
            Method::Analytic,
            "triangle scene: exact analytic coverage intervals".to_string(),
        )
    };
    AutoChoice {
        method,
        note: format!("method auto: using {method} ({why})"),
    }
}
