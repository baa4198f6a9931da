//! Helpers shared by the end-to-end tests: run the built `beltcheck` binary from the
//! repository root and read what it printed; scratch files per test binary.

#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// Run `beltcheck ARGS` from the repository root.
pub fn beltcheck(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_beltcheck"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs")
}

/// Standard output as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A scratch path `name` in a directory of its own for this test process (`tag` keeps
/// the test binaries apart).
pub fn temp(tag: &str, name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("beltcheck-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}
