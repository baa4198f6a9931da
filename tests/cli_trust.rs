//! Issue 12 through the built binary: every exit 0 is a trustworthy answer. Unusable
//! studies and usage errors exit 2 and write nothing; `--json` never replaces a link, a
//! FIFO, a device or a directory and leaves no temporary file; flags the method does not
//! use are refused; a transient cut off by `fem.max_steps` says so.

use std::path::{Path, PathBuf};

mod common;
use common::{beltcheck, stderr, stdout};

fn temp(name: &str) -> PathBuf {
    common::temp("cli-trust", name)
}

fn catalogue(name: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.json"))).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn write_scene(name: &str, v: &serde_json::Value) -> PathBuf {
    let p = temp(name);
    std::fs::write(&p, serde_json::to_string_pretty(v).unwrap()).unwrap();
    p
}

/// Exit status 2 with `needle` in the error, no panic.
fn fails_with(args: &[&str], needle: &str) -> String {
    let o = beltcheck(args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {}\n{err}", stdout(&o));
    assert!(err.contains(needle), "{args:?}: `{needle}` not in: {err}");
    assert!(!err.contains("panicked"), "{err}");
    err
}

/// The files of a directory whose name ends in `.partial`.
fn partials(dir: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(dir).unwrap().filter_map(|e| e.ok().map(|e| e.path())).filter(|p| p.to_string_lossy().ends_with(".partial")).collect()
}

/// The catalogue's string drive as a transient with this `fem` block.
fn transient_drive(fem: serde_json::Value) -> serde_json::Value {
    let mut v = catalogue("string-drive");
    v["analysis"] = serde_json::json!("transient");
    v.as_object_mut().unwrap().remove("bvp");
    v["fem"] = fem;
    v
}

/// The string drive with a torque far above its friction capacity: no solution by
/// either method.
fn unsolvable_drive() -> PathBuf {
    let mut v = catalogue("string-drive");
    v["name"] = serde_json::json!("overloaded-drive");
    v["drive"]["driven_torque"] = serde_json::json!(1000.0);
    write_scene("overloaded.json", &v)
}

#[test]
fn json_never_replaces_a_symlink_fifo_device_or_directory() {
    let dir = temp("targets");
    std::fs::create_dir_all(&dir).unwrap();
    // a symlink to a regular file: refused, the link and its target untouched
    let target = dir.join("target.json");
    std::fs::write(&target, "keep").unwrap();
    let link = dir.join("link.json");
    let _ = std::fs::remove_file(&link);
    std::os::unix::fs::symlink(&target, &link).unwrap();
    fails_with(&["solve", "scenes/string-hanging.json", "--json", link.to_str().unwrap()], "a symbolic link");
    assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep");
    // a FIFO (never opened: the refusal comes first)
    let fifo = dir.join("fifo.json");
    let _ = std::fs::remove_file(&fifo);
    let made = std::process::Command::new("mkfifo").arg(&fifo).status().map(|s| s.success()).unwrap_or(false);
    if made {
        fails_with(&["solve", "scenes/string-hanging.json", "--json", fifo.to_str().unwrap()], "not a regular file");
        assert!(!std::fs::symlink_metadata(&fifo).unwrap().file_type().is_file(), "the FIFO was replaced");
    }
    // a device
    fails_with(&["solve", "scenes/string-hanging.json", "--json", "/dev/null"], "not a regular file");
    assert!(!std::fs::symlink_metadata("/dev/null").unwrap().file_type().is_file());
    // an existing directory: refused, no `.partial` left beside it
    let sub = dir.join("out.json");
    std::fs::create_dir_all(&sub).unwrap();
    fails_with(&["solve", "scenes/string-hanging.json", "--json", sub.to_str().unwrap()], "a directory");
    assert!(sub.is_dir());
    assert!(partials(&dir).is_empty(), "{:?}", partials(&dir));
    // a missing parent directory: the write fails, nothing is left
    let missing = dir.join("no-such-dir/out.json");
    fails_with(&["solve", "scenes/string-hanging.json", "--json", missing.to_str().unwrap()], "writing");
    assert!(!dir.join("no-such-dir").exists());
    // a regular file is replaced, with no temporary file left
    let plain = dir.join("plain.json");
    std::fs::write(&plain, "old").unwrap();
    let o = beltcheck(&["solve", "scenes/string-hanging.json", "--json", plain.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::read_to_string(&plain).unwrap().contains("\"converged\": true"));
    assert!(partials(&dir).is_empty());
}

/// `converge` on a scene without a solution exits 2 and writes no study JSON.
#[test]
fn converge_on_an_unsolvable_scene_writes_nothing() {
    let scene = unsolvable_drive();
    let out = temp("unsolvable-study.json");
    let _ = std::fs::remove_file(&out);
    fails_with(&["converge", scene.to_str().unwrap(), "--tolerances", "1e-4", "--elements", "8", "--json", out.to_str().unwrap()], "reference");
    assert!(!out.exists(), "a study JSON was written for an unusable study");
}

/// A BVP tolerance the solvers refuse (below 1e-13 or above 1e-2) is refused before
/// the study runs, alone (1e-16: every BVP run would fail) or among valid ones (1e-300
/// next to 1e-4 ran, failed those rows and exited 0 before); nothing is written.
#[test]
fn converge_refuses_a_bvp_tolerance_out_of_the_solvers_range() {
    let out = temp("tight-study.json");
    for tolerances in ["1e-16", "1e-300,1e-4", "1e-4,0.05"] {
        let _ = std::fs::remove_file(&out);
        fails_with(&["converge", "scenes/string-hanging.json", "--tolerances", tolerances, "--elements", "16", "--json", out.to_str().unwrap()], "a BVP tolerance, 1e-13 < tolerance ≤ 0.01");
        assert!(!out.exists(), "{tolerances}: nothing written");
    }
}

/// `report`: a scene named `..` is refused by the scene itself; two scenes of one name
/// are refused before anything runs; a scene without a solution exits 2 like `converge`.
#[test]
fn report_names_duplicates_and_exit_status() {
    let mut v = catalogue("string-hanging");
    v["name"] = serde_json::json!("..");
    let dotdot = write_scene("dotdot.json", &v);
    let out = temp("report-dotdot");
    fails_with(&["report", "-o", out.to_str().unwrap(), dotdot.to_str().unwrap()], "`name`");
    assert!(!out.exists());

    let twin = write_scene("twin.json", &catalogue("string-hanging"));
    let out = temp("report-twins");
    fails_with(&["report", "-o", out.to_str().unwrap(), "scenes/string-hanging.json", twin.to_str().unwrap()], "appears twice");
    assert!(!out.exists(), "nothing may run or be written");

    let scene = unsolvable_drive();
    let out = temp("report-unsolvable");
    fails_with(&["report", "-o", out.to_str().unwrap(), "--tolerances", "1e-4", "--elements", "8", scene.to_str().unwrap()], "overloaded-drive");
}

/// `gate`: usage and input errors exit 2, drift exits 1.
#[test]
fn gate_tells_input_errors_from_drift() {
    let missing = temp("no-such-scene.json");
    fails_with(&["gate", "--bvp-only", missing.to_str().unwrap()], "cannot read");
    let garbage = temp("garbage.json");
    std::fs::write(&garbage, "{ not json").unwrap();
    fails_with(&["gate", "--bvp-only", garbage.to_str().unwrap()], "not valid JSON");
    fails_with(&["gate", "--bvp-only", "--tolerance", "2", "scenes/string-hanging.json"], "--tolerance");
    fails_with(&["gate", "--formulation", "no-such-element", "scenes/string-hanging.json"], "no-such-element");
    // drift: a limit no run can meet
    let mut v = catalogue("string-hanging");
    v["gate"] = serde_json::json!({"tolerances": {"y_upper_mid": 1e-300}});
    let strict = write_scene("strict-gate.json", &v);
    let o = beltcheck(&["gate", "--bvp-only", strict.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}\n{}", stdout(&o), stderr(&o));
    assert!(stdout(&o).contains("FAILED"), "{}", stdout(&o));
}

/// A duplicate key in a scene file is a named error through the CLI.
#[test]
fn duplicate_key_through_the_cli() {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/string-hanging.json")).unwrap();
    let scene = temp("dup.json");
    std::fs::write(&scene, text.replacen("\"length\": 1.41", "\"length\": 1.41, \"length\": 99", 1)).unwrap();
    let out = temp("dup.out.json");
    let _ = std::fs::remove_file(&out);
    fails_with(&["solve", scene.to_str().unwrap(), "--json", out.to_str().unwrap()], "duplicate key `belt.length`");
    assert!(!out.exists());
}

/// Flags the chosen method does not use are errors; element, sample and field counts
/// are bounded.
#[test]
fn flags_for_another_method_and_out_of_range_counts() {
    let s = "scenes/string-hanging.json";
    fails_with(&["solve", s, "--method", "bvp-shooting", "--scheme", "bogus"], "--scheme is not used by method bvp-shooting");
    fails_with(&["solve", s, "--method", "fem", "--scheme", "gauss6"], "--scheme is not used by method fem");
    fails_with(&["solve", s, "--method", "fem", "--tolerance", "1e-6"], "--tolerance is not used by method fem");
    fails_with(&["solve", s, "--elements", "0"], "--elements is not used by method bvp-collocation");
    fails_with(&["solve", s, "--method", "bvp-collocation", "--formulation", "string-gauss"], "--formulation is not used");
    fails_with(&["solve", s, "--method", "fem", "--elements", "0"], "4 … 16384");
    fails_with(&["solve", s, "--method", "fem", "--elements", "1048576"], "4 … 16384");
    fails_with(&["solve", s, "--fields", "10000000"], "--fields");
    fails_with(&["solve", s, "--tolerance", "0"], "0 < tolerance < 1");
    fails_with(&["converge", s, "--samples", "10000000"], "16 … 100000");
    fails_with(&["converge", s, "--samples", "3"], "16 … 100000");
    fails_with(&["converge", s, "--elements", "8,2000000"], "4 … 16384");
}

/// A formulation of another belt theory is refused for every scene, and `--method fem`
/// without `--formulation` takes the scene's belt theory's default.
#[test]
fn formulations_follow_the_belt_theory() {
    for (scene, f) in [("string-drive", "rod-simpson"), ("string-drive", "rod-gauss"), ("string-hanging", "rod-simpson"), ("rod-hanging", "string-simpson")] {
        let out = temp(&format!("{scene}-{f}.json"));
        let _ = std::fs::remove_file(&out);
        fails_with(&["solve", &format!("scenes/{scene}.json"), "--method", "fem", "--formulation", f, "--elements", "32", "--json", out.to_str().unwrap()], "discretises theory");
        assert!(!out.exists());
    }
    // a rod scene without `fem.formulations` gets a rod formulation
    let mut v = catalogue("rod-hanging");
    v.as_object_mut().unwrap().remove("fem");
    let scene = write_scene("rod-no-fem.json", &v);
    let o = beltcheck(&["solve", scene.to_str().unwrap(), "--method", "fem", "--elements", "64"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("fem rod-"), "{}", stdout(&o));
}

/// A transient cut off by `fem.max_steps` is no steady state: `"converged": false` in
/// the JSON and a statement in the printout (it used to say `true`, silently).
#[test]
fn transient_cut_off_by_max_steps_is_not_converged() {
    let scene = write_scene("cut-transient.json", &transient_drive(serde_json::json!({"elements": 32, "max_steps": 1})));
    let out = temp("cut-transient.out.json");
    let o = beltcheck(&["solve", scene.to_str().unwrap(), "--method", "fem", "--json", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("NOT CONVERGED"), "{}", stdout(&o));
    assert!(stderr(&o).contains("did not reach a steady state"), "{}", stderr(&o));
    let r: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(r["converged"], false);
    // with the default step limit the same transient reaches its steady state
    let scene = write_scene("full-transient.json", &transient_drive(serde_json::json!({"elements": 32})));
    let o = beltcheck(&["solve", scene.to_str().unwrap(), "--method", "fem", "--json", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stdout(&o).contains("NOT CONVERGED"));
    let r: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(r["converged"], true);
}

/// A transient time step in which the driver turns more than π/4 is refused (ω₁ = 60
/// rad/s, Δt = 0.1 s: 6 rad per step).
#[test]
fn coarse_time_step_is_refused() {
    let scene = write_scene("coarse-step.json", &transient_drive(serde_json::json!({"elements": 32, "time_step": 0.1})));
    fails_with(&["solve", scene.to_str().unwrap(), "--method", "fem"], "fem.time_step");
}

/// Numbers in error messages are printed with significant digits (issue 12, "smaller
/// ones"): a tolerance of 1e-16 is named as `1e-16`, not as sixteen fixed digits.
#[test]
fn numbers_in_messages_have_significant_digits() {
    let err = fails_with(&["solve", "scenes/string-hanging.json", "--tolerance", "1e-16"], "tolerance = 1e-16");
    assert!(!err.contains("0000000"), "a long run of fixed digits in: {err}");
}

/// Issue 12 audit: a formulation of another belt theory is a usage error before anything
/// runs in `gate`, `converge` and `report`, as in `solve` — `gate` used to run the study and
/// exit 1 ("drift") with a failed FE row, from `--formulation` or from the scene's
/// `fem.formulations`.
#[test]
fn studies_refuse_a_formulation_of_another_theory() {
    let s = "scenes/string-hanging.json";
    fails_with(&["gate", "--formulation", "rod-simpson", s], "discretises theory `kirchhoff`");
    let mut v = catalogue("string-hanging");
    v["fem"] = serde_json::json!({"formulations": ["rod-gauss"]});
    let scene = write_scene("string-with-rod-formulation.json", &v);
    fails_with(&["gate", scene.to_str().unwrap()], "discretises theory `kirchhoff`");
    let out = temp("rod-formulation-study.json");
    let _ = std::fs::remove_file(&out);
    fails_with(&["converge", scene.to_str().unwrap(), "--tolerances", "1e-4", "--json", out.to_str().unwrap()], "discretises theory `kirchhoff`");
    assert!(!out.exists());
    fails_with(&["converge", "scenes/rod-hanging.json", "--reference", "richardson", "--formulation", "string-gauss", "--elements", "16,32,64"], "discretises theory `string`");
    let dir = temp("report-rod-formulation");
    fails_with(&["report", "-o", dir.to_str().unwrap(), scene.to_str().unwrap()], "discretises theory `kirchhoff`");
    assert!(!dir.exists(), "nothing may run or be written");
}

/// Issue 12 audit: two scene names that differ only in letter case write one report
/// directory on a case-insensitive file system (macOS, Windows) — refused like equal names.
#[test]
fn report_refuses_names_equal_but_for_case() {
    let mut v = catalogue("string-hanging");
    v["name"] = serde_json::json!("String-Hanging");
    let twin = write_scene("case-twin.json", &v);
    let out = temp("report-case-twins");
    fails_with(&["report", "-o", out.to_str().unwrap(), "scenes/string-hanging.json", twin.to_str().unwrap()], "appears twice");
    assert!(!out.exists());
}
