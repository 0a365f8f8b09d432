//! Effects analysis: which stages does a scene call for?
//!
//! Per object: moving or static (in 2DH, so camera motion moves everything), opaque or
//! transparent, textured or flat, triangles or splats; per pair: can they interpenetrate
//! during the shutter (do their swept world-space bounding boxes overlap; linear motion keeps
//! every in-between position inside the box of both ends). The result is an [`Effects`]
//! report and a [`Pipeline`] naming the stages a method must run.

use std::fmt;

use crate::prepared::PreparedScene;

/// What an object is made of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ObjectKind {
    /// A triangle mesh with this many triangles.
    Triangles(usize),
    /// A splat object with this many splats.
    Splats(usize),
}

/// The analysis of one object.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObjectEffects {
    /// The object's name.
    pub name: String,
    /// Triangles or splats.
    pub kind: ObjectKind,
    /// Some vertex moves in 2DH or depth during the shutter (object or camera motion).
    pub moving: bool,
    /// The object itself moves in the world (its own motion, not only the camera's).
    pub world_moving: bool,
    /// Some surface has alpha < 1 (material or texture).
    pub transparent: bool,
    /// The material has a texture.
    pub textured: bool,
    /// The material is lit ([`crate::lighting`]).
    pub lit: bool,
}

/// The analysis of a whole scene.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Effects {
    /// Triangle objects first, then splat objects, in scene order.
    pub objects: Vec<ObjectEffects>,
    /// The camera pose differs between open and close.
    pub camera_moving: bool,
    /// Pairs of objects (indices into `objects`), at least one of them moving, whose swept
    /// bounds overlap: their depth order may change during the shutter.
    pub overlapping_pairs: Vec<(usize, usize)>,
    /// Number of lights in the scene.
    pub lights: usize,
    /// Some light moves over the shutter.
    pub lights_moving: bool,
}

/// The stages a rendering method has to run for a scene (the others are skipped).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Pipeline {
    /// Some objects are static and can take the ordinary static rasteriser path.
    pub static_path: bool,
    /// Some objects move: per-pixel time intervals (or time samples) are needed.
    pub motion: bool,
    /// Some surfaces are transparent: sorted blending instead of opaque insertion.
    pub transparency: bool,
    /// Some pair of objects may interpenetrate: intersection handling in the resolve.
    pub intersection: bool,
    /// Some material is textured: texture integration.
    pub textures: bool,
    /// Some material is lit: normals, lights and per-interval shading.
    pub lighting: bool,
    /// Some objects are splats.
    pub splats: bool,
    /// Interval storage is needed at all (false for a fully static opaque scene).
    pub interval_storage: bool,
}

impl Effects {
    /// Analyses a prepared scene.
    pub fn analyse(scene: &PreparedScene) -> Effects {
        let mut objects = Vec::new();
        for o in &scene.objects {
            let tris = scene.triangles.get(o.range.clone()).unwrap_or(&[]);
            let mat = scene.materials.get(o.material as usize);
            let tex = mat.and_then(|m| scene.texture_of(m));
            objects.push(ObjectEffects {
                name: o.name.clone(),
                kind: ObjectKind::Triangles(tris.len()),
                moving: tris.iter().any(|t| t.is_moving()),
                world_moving: tris
                    .iter()
                    .any(|t| t.world_open != t.world_close || t.normal_open != t.normal_close),
                transparent: mat.is_some_and(|m| m.color[3] < 1.0)
                    || tex.is_some_and(|t| t.has_alpha()),
                textured: tex.is_some(),
                lit: scene.is_lit(o.material),
            });
        }
        for o in &scene.splat_objects {
            let splats = scene.splats.get(o.range.clone()).unwrap_or(&[]);
            objects.push(ObjectEffects {
                name: o.name.clone(),
                kind: ObjectKind::Splats(splats.len()),
                moving: splats.iter().any(|s| scene.splat_moves(s)),
                world_moving: splats.iter().any(|s| {
                    s.centre_open != s.centre_close
                        || s.normal_open != s.normal_close
                        || s.radius_open != s.radius_close
                }),
                transparent: splats.iter().any(|s| s.color[3] < 1.0),
                textured: false,
                lit: scene.is_lit(o.material),
            });
        }
        let bounds: Vec<_> = scene
            .objects
            .iter()
            .chain(&scene.splat_objects)
            .map(|o| o.swept_bounds)
            .collect();
        let mut overlapping_pairs = Vec::new();
        for i in 0..bounds.len() {
            for j in i + 1..bounds.len() {
                let ((alo, ahi), (blo, bhi)) = (bounds[i], bounds[j]);
                // Two static objects keep their depth order over time: only pairs with a
                // moving member can cross in depth during the shutter.
                let moving = objects[i].moving || objects[j].moving;
                if moving && alo.cmple(bhi).all() && blo.cmple(ahi).all() {
                    overlapping_pairs.push((i, j));
                }
            }
        }
        Effects {
            objects,
            camera_moving: scene.camera_moves(),
            overlapping_pairs,
            lights: scene.lights.len(),
            lights_moving: scene.lights_move(),
        }
    }

    /// Number of moving objects.
    pub fn moving(&self) -> usize {
        self.objects.iter().filter(|o| o.moving).count()
    }

    /// Number of transparent objects.
    pub fn transparent(&self) -> usize {
        self.objects.iter().filter(|o| o.transparent).count()
    }

    /// Number of textured objects.
    pub fn textured(&self) -> usize {
        self.objects.iter().filter(|o| o.textured).count()
    }

    /// Number of splat objects.
    pub fn splat_objects(&self) -> usize {
        self.objects
            .iter()
            .filter(|o| matches!(o.kind, ObjectKind::Splats(_)))
            .count()
    }

    /// The stages needed.
    pub fn pipeline(&self) -> Pipeline {
        let motion = self.moving() > 0;
        let transparency = self.transparent() > 0;
        let lighting = self.objects.iter().any(|o| o.lit);
        Pipeline {
            static_path: self.objects.iter().any(|o| !o.moving),
            motion,
            transparency,
            intersection: !self.overlapping_pairs.is_empty(),
            textures: self.textured() > 0,
            splats: self.splat_objects() > 0,
            lighting,
            // Moving lights change the colour of still surfaces over the shutter.
            interval_storage: motion || transparency || (lighting && self.lights_moving),
        }
    }
}

fn plural(n: usize, one: &str) -> String {
    let es = if one.ends_with('h') || one.ends_with('s') {
        "es"
    } else {
        "s"
    };
    if n == 1 {
        format!("1 {one}")
    } else {
        format!("{n} {one}{es}")
    }
}

fn names(e: &Effects, pick: impl Fn(&ObjectEffects) -> bool) -> String {
    let list: Vec<&str> = e
        .objects
        .iter()
        .filter(|o| pick(o))
        .map(|o| o.name.as_str())
        .collect();
    match list.len() {
        0 => String::new(),
        1..=4 => format!(" ({})", list.join(", ")),
        n => format!(" ({}, ... {} more)", list[..3].join(", "), n - 3),
    }
}

impl fmt::Display for Effects {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (mut nt, mut tris, mut ns, mut splats) = (0, 0, 0, 0);
        for o in &self.objects {
            match o.kind {
                ObjectKind::Triangles(n) => (nt, tris) = (nt + 1, tris + n),
                ObjectKind::Splats(n) => (ns, splats) = (ns + 1, splats + n),
            }
        }
        writeln!(
            f,
            "scene: {} with {}, {} with {}",
            plural(nt, "triangle mesh"),
            plural(tris, "triangle"),
            plural(ns, "splat object"),
            plural(splats, "splat")
        )?;
        let p = self.pipeline();
        let with_camera = |o: &ObjectEffects| o.moving && !o.world_moving;
        writeln!(
            f,
            "motion: {}{}{}",
            plural(
                self.objects.iter().filter(|o| o.world_moving).count(),
                "object"
            ),
            names(self, |o| o.world_moving),
            if self.camera_moving {
                format!(
                    "; the camera moves, so {} moving on screen{}",
                    plural(self.moving(), "object"),
                    if self.objects.iter().any(with_camera) {
                        format!(", with the camera only{}", names(self, with_camera))
                    } else {
                        String::new()
                    }
                )
            } else {
                String::new()
            }
        )?;
        writeln!(
            f,
            "static path: {}{}",
            plural(self.objects.len() - self.moving(), "object"),
            names(self, |o| !o.moving)
        )?;
        writeln!(
            f,
            "transparency: {}{}",
            plural(self.transparent(), "object"),
            names(self, |o| o.transparent)
        )?;
        writeln!(
            f,
            "textures: {}{}",
            plural(self.textured(), "object"),
            names(self, |o| o.textured)
        )?;
        let lit = self.objects.iter().filter(|o| o.lit).count();
        writeln!(
            f,
            "lighting: {}{}, {}{}",
            plural(lit, "lit object"),
            names(self, |o| o.lit),
            plural(self.lights, "light"),
            if self.lights_moving { " (moving)" } else { "" }
        )?;
        if self.overlapping_pairs.is_empty() {
            writeln!(
                f,
                "intersection handling: off (no overlapping swept bounds)"
            )?;
        } else {
            let shown: Vec<String> = self
                .overlapping_pairs
                .iter()
                .take(4)
                .map(|&(i, j)| format!("{}/{}", self.objects[i].name, self.objects[j].name))
                .collect();
            let more = self.overlapping_pairs.len().saturating_sub(4);
            writeln!(
                f,
                "intersection handling: on for {} ({}{})",
                plural(self.overlapping_pairs.len(), "pair"),
                shown.join(", "),
                if more > 0 {
                    format!(", ... {more} more")
                } else {
                    String::new()
                }
            )?;
        }
        writeln!(
            f,
            "splats: {}{}",
            plural(self.splat_objects(), "object"),
            names(self, |o| matches!(o.kind, ObjectKind::Splats(_)))
        )?;
        write!(
            f,
            "interval storage: {}",
            if p.interval_storage {
                "needed"
            } else {
                "none (static opaque scene)"
            }
        )
    }
}
