//! The worker threads of a render or a comparison: the renderer runs on rayon's current
//! pool, and `mblur render` and `mblur compare` install one of the size asked for.

use mblur_scene::{Error, Result};

/// The most worker threads accepted, per core of the machine: more only add overhead (a
/// 64 x 48 image on 100 000 threads took minutes).
pub const THREADS_PER_CORE: usize = 4;

/// The thread pool of `--threads` (all cores when absent), refused above
/// [`THREADS_PER_CORE`] per core.
pub fn thread_pool(threads: Option<usize>) -> Result<rayon::ThreadPool> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let max = THREADS_PER_CORE * cores;
    let bad = |message: String| Error::Option {
        option: "--threads".into(),
        message,
    };
    let n = match threads {
        None => cores,
        Some(n) if n == 0 || n > max => {
            return Err(bad(format!(
                "must be between 1 and {max} ({THREADS_PER_CORE} per core on this {cores}-core machine), got {n}"
            )));
        }
        Some(n) => n,
    };
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .map_err(|e| bad(e.to_string()))
}
