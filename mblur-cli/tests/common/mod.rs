//! The command under test, shared by the `mblur` command's test files (it needs this crate's
//! binary, so it cannot live in the workspace's shared test library, `integration-tests`);
//! the file-listing helper is that library's, re-exported so every test file imports both
//! from here.
#![allow(dead_code, unused_imports)]

use assert_cmd::Command;

pub use integration_tests::files;

/// The `mblur` command built from this crate.
pub fn mblur() -> Command {
    Command::new(env!("CARGO_BIN_EXE_mblur"))
}
