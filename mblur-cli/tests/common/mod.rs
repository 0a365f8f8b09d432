//! The command under test and the files it leaves, shared by the `mblur` command's test
//! files.
#![allow(dead_code)]

use assert_cmd::Command;

/// The `mblur` command built from this crate.
pub fn mblur() -> Command {
    Command::new(env!("CARGO_BIN_EXE_mblur"))
}

/// The names of the files in `dir`, sorted.
pub fn files(dir: &std::path::Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}
