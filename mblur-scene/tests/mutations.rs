//! Hostile scene files, generated: every built-in scene with one field dropped, or one value
//! replaced by another type, a non-finite-looking or out-of-range number, -0, a huge count or
//! an empty container. Each mutant must either load and render (at a small size, with the
//! method `auto` picks) to finite, non-negative pixels, or fail with an error that names the
//! scene file, and never panic.

use mblur::{MethodOptions, NoProgress};
use mblur_scene::{Error, Scene, builtin};
use proptest::prelude::*;
use serde_json::Value;

/// The label the mutants are loaded under: every error about them must name it.
const FILE: &str = "mutant.json";

/// Values that replace a field: wrong types, extreme and special numbers, huge counts.
fn hostile() -> Vec<Value> {
    let num = |s: &str| serde_json::from_str::<Value>(s).unwrap();
    vec![
        Value::Null,
        Value::Bool(true),
        Value::String("NaN".into()),
        Value::Array(Vec::new()),
        Value::Object(serde_json::Map::new()),
        num("0"),
        num("-1"),
        num("-0.0"),
        num("1e308"),
        num("-1e308"),
        num("1e-308"),
        num("5e-324"),
        num("4294967296"),
        num("18446744073709551615"),
    ]
}

/// Every path (object keys and array indices) in `v`, parents before children.
fn paths(v: &Value, prefix: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    match v {
        Value::Object(m) => {
            for (k, child) in m {
                prefix.push(Step::Key(k.clone()));
                out.push(prefix.clone());
                paths(child, prefix, out);
                prefix.pop();
            }
        }
        Value::Array(a) => {
            for (i, child) in a.iter().enumerate() {
                prefix.push(Step::Index(i));
                out.push(prefix.clone());
                paths(child, prefix, out);
                prefix.pop();
            }
        }
        _ => {}
    }
}

/// One step of a path into a JSON document.
#[derive(Debug, Clone)]
enum Step {
    Key(String),
    Index(usize),
}

/// Drops the field at `path` (`replacement` None) or replaces it.
fn mutate(root: &mut Value, path: &[Step], replacement: Option<Value>) {
    let (last, parents) = path.split_last().expect("non-empty path");
    let mut v = root;
    for s in parents {
        v = match s {
            Step::Key(k) => &mut v[k.as_str()],
            Step::Index(i) => &mut v[*i],
        };
    }
    match (last, v, replacement) {
        (Step::Key(k), Value::Object(m), None) => {
            m.remove(k);
        }
        (Step::Index(i), Value::Array(a), None) => {
            a.remove(*i);
        }
        (Step::Key(k), Value::Object(m), Some(r)) => {
            m.insert(k.clone(), r);
        }
        (Step::Index(i), Value::Array(a), Some(r)) => a[*i] = r,
        _ => unreachable!("paths() only yields keys of objects and indices of arrays"),
    }
}

/// The error must say which file it is about (a mesh or texture file it refers to counts).
fn assert_names_file(e: &Error, json: &str) {
    let text = e.to_string();
    let named = match e {
        Error::Read { .. } | Error::Format { .. } => true,
        Error::Render(_) => true,
        _ => text.starts_with(&format!("{FILE}: ")),
    };
    assert!(named, "error does not name {FILE}: {text}\n{json}");
}

/// Built-in scenes whose mutants are parsed and validated, not prepared and rendered: the
/// meshes of the first three take long to build (the light scenes exercise the same code).
/// The splat scenes are here for a known unbounded case: the EWA A-buffer's time grows with
/// the square of the splats overlapping a pixel, and some mutants still put thousands of
/// splats in every pixel of the 16 x 12 image (minutes each). A splat radius beyond the whole
/// point set is refused at load (`mblur-cli/tests/bad_input.rs`), but a time bound on the
/// A-buffer is open work, not something this test may hide by timing out.
const HEAVY: [&str; 5] = [
    "clothball",
    "clothball-ronnow",
    "fence",
    "splat-ball",
    "splat-mix",
];

/// Loads, resizes, prepares and renders a mutant (only loads it when `load_only`); panics
/// only on a broken promise.
fn check(json: &str, load_only: bool) {
    let scene = match Scene::from_json(json, FILE, "") {
        Ok(s) => s,
        Err(e) => return assert_names_file(&e, json),
    };
    let mut scene = scene;
    if let Err(e) = scene.set_size(Some(16), Some(12)) {
        return assert_names_file(&e, json);
    }
    if load_only {
        return;
    }
    let prepared = match scene.prepare() {
        Ok(p) => p,
        Err(e) => return assert_names_file(&e, json),
    };
    if prepared.triangles.len() + prepared.splats.len() > 200_000 {
        // A valid but huge mutant (a count raised within its limit): loading it was the test.
        return;
    }
    match mblur::render(&prepared, &MethodOptions::default(), &NoProgress) {
        Ok(out) => assert!(
            out.image
                .pixels
                .iter()
                .flatten()
                .all(|c| c.is_finite() && *c >= 0.0),
            "non-finite or negative pixel from\n{json}"
        ),
        Err(e) => assert!(!e.to_string().is_empty()),
    }
}

fn cases() -> u32 {
    // Each case prepares and renders a whole built-in scene: a few hundred cases cover every
    // field of every scene several times over (the exhaustive test below covers one scene).
    if std::env::var_os("MBLUR_DEEP").is_some() {
        160
    } else {
        64
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    #[test]
    fn mutated_builtin_scenes_load_and_render_or_name_the_file(
        scene in 0..builtin::SCENES.len(),
        at in any::<prop::sample::Index>(),
        what in 0..15usize,
    ) {
        let (name, _, json) = builtin::SCENES[scene];
        let mut doc: Value = serde_json::from_str(json).unwrap();
        let mut all = Vec::new();
        paths(&doc, &mut Vec::new(), &mut all);
        let path = &all[at.index(all.len())];
        let replacement = hostile().into_iter().nth(what);
        mutate(&mut doc, path, replacement);
        let text = serde_json::to_string_pretty(&doc).unwrap();
        check(&text, HEAVY.contains(&name));
    }
}

#[test]
fn every_hostile_value_at_every_field_of_one_scene() {
    // An exhaustive pass over a small scene: every field of crossing-quads, dropped and
    // replaced by each hostile value.
    let json = builtin::json("crossing-quads").unwrap();
    let doc: Value = serde_json::from_str(json).unwrap();
    let mut all = Vec::new();
    paths(&doc, &mut Vec::new(), &mut all);
    for path in &all {
        for replacement in std::iter::once(None).chain(hostile().into_iter().map(Some)) {
            let mut d = doc.clone();
            mutate(&mut d, path, replacement);
            check(&serde_json::to_string_pretty(&d).unwrap(), false);
        }
    }
}
