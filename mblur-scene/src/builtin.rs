//! Built-in scenes, embedded in the binary from `scenes/*.json`.

/// `(name, description, JSON)` of every built-in scene; the first is the default.
pub const SCENES: [(&str, &str, &str); 13] = [
    (
        "billiards",
        "balls rolling and spinning fast across a table (Gribel 2010, Fig. 14)",
        include_str!("../scenes/billiards.json"),
    ),
    (
        "fence",
        "a fence moving 500 px per frame in front of a checkerboard (Gribel 2010, Fig. 11)",
        include_str!("../scenes/fence.json"),
    ),
    (
        "transparent-cubes",
        "overlapping transparent cubes moving and spinning (Gribel 2010, Fig. 12)",
        include_str!("../scenes/transparent-cubes.json"),
    ),
    (
        "crossing-quads",
        "two quads that pass through each other during the shutter (Ronnow, Fig. 11)",
        include_str!("../scenes/crossing-quads.json"),
    ),
    (
        "pills",
        "opaque and transparent pills over a moving background (Ronnow, Fig. 9/16)",
        include_str!("../scenes/pills.json"),
    ),
    (
        "clothball",
        "a wrinkled ball of about 64k triangles, spinning 35 degrees and moving ~400 px at 1024x1024: 33x the intervals of Ronnow's clothball (Ronnow, Table 1)",
        include_str!("../scenes/clothball.json"),
    ),
    (
        "clothball-ronnow",
        "Ronnow's clothball: a transparent cloth falling onto a rotating opaque ball, 65k triangles, with about Ronnow's amount of motion (Ronnow 2021, Fig. 1, Table 1)",
        include_str!("../scenes/clothball-ronnow.json"),
    ),
    (
        "textured-quad",
        "a rotating checker-textured quad (Ronnow, Fig. 8)",
        include_str!("../scenes/textured-quad.json"),
    ),
    (
        "spinning-wheel",
        "a checker-textured wheel turning 350 degrees while translating: curved motion cut into segments",
        include_str!("../scenes/spinning-wheel.json"),
    ),
    (
        "spinning-lit-ball",
        "a Blinn-Phong ball turning 150 degrees while it crosses the frame under a fixed light: where shading once per interval fails",
        include_str!("../scenes/spinning-lit-ball.json"),
    ),
    (
        "splat-ball",
        "a ball of point splats flying past (Heinzle)",
        include_str!("../scenes/splat-ball.json"),
    ),
    (
        "splat-mix",
        "a ball of splats passing behind a moving box and in front of a post, over a textured backdrop (Heinzle splats with Gribel triangles)",
        include_str!("../scenes/splat-mix.json"),
    ),
    (
        "static",
        "nothing moves: the static path only",
        include_str!("../scenes/static.json"),
    ),
];

/// The default scene.
pub const DEFAULT_SCENE: &str = "billiards";

/// Appended to the name of a built-in scene with lights, it names the same scene unlit: no
/// lights, every material `unlit` (e.g. `billiards-unlit`).
pub const UNLIT_SUFFIX: &str = "-unlit";

/// The JSON of a built-in scene (without [`UNLIT_SUFFIX`]).
pub fn json(name: &str) -> Option<&'static str> {
    SCENES.iter().find(|s| s.0 == name).map(|s| s.2)
}

/// The JSON of built-in scene `name` and whether it is asked for unlit: `name` itself, or
/// `name` without [`UNLIT_SUFFIX`] when that is a built-in scene with lights.
pub fn lookup(name: &str) -> Option<(&'static str, bool)> {
    if let Some(j) = json(name) {
        return Some((j, false));
    }
    let base = name.strip_suffix(UNLIT_SUFFIX)?;
    let j = json(base)?;
    j.contains("\"lights\"").then_some((j, true))
}
