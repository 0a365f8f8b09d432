//! How `--method auto` (the default) picks a method for a scene, from what the scene is
//! made of and the [`Pipeline`] its effects call for:
//!
//! 1. splats only: `ewa` (Heinzle 2010), the only method that renders splats as splats;
//! 2. splats and triangles together: `ewa`, which renders the splats as EWA splats and
//!    composites the triangles, swept by the analytic chain (Gribel 2010), in the same
//!    A-buffer as surface intervals;
//!    in both cases, when `ewa` refuses the scene (transparent splats, a shutter response
//!    other than the box), `accum` (it renders splats as discs), with ewa's reason in the note;
//! 3. a fully static opaque triangle scene: `analytic`, which takes the static path for it
//!    (one static render, no interval storage at all);
//! 4. any other triangle scene: `analytic` (edge-eqn -> interval-buffer -> resolve, exact
//!    interval lists; Gribel 2010), which supports motion of objects and camera,
//!    transparency, textures, interpenetration and the near plane.

use crate::effects::Pipeline;
use crate::method::Method;
use crate::prepared::PreparedScene;

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
/// use mblur::{Effects, Method};
/// use mblur_scene::Scene;
/// let scene = Scene::builtin("splat-ball")?.prepare()?;
/// let choice = mblur::auto::choose(&scene, &Effects::analyse(&scene).pipeline());
/// assert_eq!(choice.method, Method::Ewa);
/// # Ok::<(), mblur_scene::Error>(())
/// ```
pub fn choose(scene: &PreparedScene, pipeline: &Pipeline) -> AutoChoice {
    let (method, why) = if crate::ewa::accepts(scene) {
        let why = if scene.triangles.is_empty() {
            "every object is a splat".to_string()
        } else {
            format!(
                "the scene mixes {} triangles and {} splats; ewa renders the splats as EWA splats and composites the motion-blurred triangles from the analytic chain in its A-buffer",
                scene.triangles.len(),
                scene.splats.len()
            )
        };
        (Method::Ewa, why)
    } else if !scene.splats.is_empty() {
        let reason = crate::ewa::check_scene(scene)
            .err()
            .map_or_else(String::new, |e| e.to_string());
        (
            Method::Accum,
            format!(
                "the scene has {} splats{} and ewa refuses it ({reason}); accum renders splats as discs",
                scene.splats.len(),
                if scene.triangles.is_empty() {
                    String::new()
                } else {
                    format!(" and {} triangles", scene.triangles.len())
                }
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
