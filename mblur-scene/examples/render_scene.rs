//! Render a scene from code: a built-in scene (or a scene file given as the first argument)
//! to `render_scene.png`.
//!
//! `cargo run --release -p mblur-scene --example render_scene -- [SCENE.json]`

fn main() -> Result<(), mblur_scene::Error> {
    let scene = match std::env::args().nth(1) {
        Some(path) => mblur_scene::Scene::load(path)?,
        None => mblur_scene::Scene::builtin("crossing-quads")?,
    };
    let options = mblur::MethodOptions::defaults(mblur::Method::Accum);
    let out = mblur::render(&scene.prepare()?, &options, &mblur::NoProgress)?;
    println!("{}\n{}", out.effects, out.description);
    mblur_scene::image_io::save(&out.image, std::path::Path::new("render_scene.png"))?;
    println!("wrote render_scene.png");
    Ok(())
}
