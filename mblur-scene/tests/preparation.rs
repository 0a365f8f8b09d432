//! Preparation runs parts of its work in parallel on rayon's current pool (the automatic
//! segment tests over vertices, each object's frames, projections, smooth normals and
//! triangles): the prepared scene must not depend on how many threads that pool has.

use mblur_scene::Scene;

/// The scene prepared on a pool of `threads` threads, as exact text (`{:?}` of an f64
/// round-trips, so equal text is equal bits).
fn prepared(scene: &Scene, threads: usize) -> (String, Vec<u32>) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    let p = pool
        .install(|| scene.prepare())
        .expect("the scene prepares");
    let segments = p.objects.iter().map(|o| o.segments).collect();
    (format!("{:?}", p.triangles), segments)
}

#[test]
fn preparation_does_not_depend_on_the_thread_count() {
    // Automatic segments on a curved path (the wheel: dozens), smooth normals (the lit
    // ball), straight motion and several objects (billiards).
    for name in ["spinning-wheel", "spinning-lit-ball", "billiards"] {
        let scene = Scene::builtin(name).expect("a built-in scene");
        let one = prepared(&scene, 1);
        assert!(
            one.1.iter().any(|&s| s > 1) || name == "billiards",
            "{name}: {:?}",
            one.1
        );
        for threads in [2, 3] {
            assert!(
                one == prepared(&scene, threads),
                "{name} on {threads} threads"
            );
        }
    }
}
