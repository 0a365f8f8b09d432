//! Render a scene from code: a built-in scene (or a scene file given as the first argument)
//! to `render_scene.png`.
//!
//! `cargo run --release -p mblur --example render_scene -- [SCENE.json]`

fn main() -> Result<(), mblur::Error> {
    let scene = match std::env::args().nth(1) {
        Some(path) => mblur::Scene::load(path)?,
        None => mblur::Scene::builtin("crossing-quads")?,
    };
    let options = mblur::RenderOptions {
        method: mblur::Method::Accum,
        ..Default::default()
    };
    let out = mblur::render(&scene.prepare()?, &options, &mblur::NoProgress)?;
    println!("{}\n{}", out.effects, out.description);
    out.image.save(std::path::Path::new("render_scene.png"))?;
    println!("wrote render_scene.png");
    Ok(())
}
