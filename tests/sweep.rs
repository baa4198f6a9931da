//! `beltcheck sweep` (docs/sweep.md, spec §3.6): the continuation along a line
//! reproduces independent solves, bad parameters are refused before anything runs, and
//! points without a solution make exit status 2.

use std::path::PathBuf;

mod common;
use common::{beltcheck, stderr, stdout};

use drive::scene::Scene;
use verification::sweep::{ParamRange, PointStatus, Sweep, SweepPlan};

fn temp(name: &str) -> PathBuf {
    common::temp("sweep", name)
}

fn cosserat_drive() -> Scene {
    Scene::from_path(std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/cosserat-drive.json"))).expect("catalogue scene")
}

/// A 1-parameter sweep over b₂ (warm starts from the previous point) gives the summary
/// of independent cold solves (the model's own homotopy) at the same points, to the
/// solver tolerance. Source: spec §3.6 (b₂ study around `cosserat-drive`).
///
/// Tolerance: the solver tolerance 1e-8 of the scene, relative (absolute 1e-11 for
/// outputs below 1e-3, the mid-span moments of 7e-4 N·m). Both runs are collocation
/// solutions with relative residual ≤ 1e-8 on their own adapted meshes (the warm run
/// keeps the previous point's mesh, the cold run builds its own); measured: 2.5e-11
/// relative at b₂ = 3.2e3, 1e4, 3.2e4 (the largest in `moment_upper_mid`). A warm start
/// that converged to another solution or on an unadapted mesh differs at 1e-3 and above.
#[test]
fn warm_started_b2_sweep_reproduces_independent_solves() {
    let scene = cosserat_drive();
    let range: ParamRange = "belt.shear_stiffness=1e3:4e3:log:3".parse().unwrap();
    let mut plan = SweepPlan::new(&scene, vec![range.clone()], 0).unwrap();
    plan.asymptotes = false;
    let sweep = Sweep::run(&scene, &plan, &|_| {});
    assert!(sweep.failures().is_empty(), "{:?}", sweep.failures());
    let line = &sweep.lines[0];
    for (i, (p, v)) in line.points.iter().zip(range.values()).enumerate() {
        let PointStatus::Solved { summary, warm, steps, failed_attempts, wall_seconds, .. } = &p.status else { panic!("point {i} not solved: {:?}", p.status) };
        // the first point is the line's cold start, every later one a warm start
        assert_eq!(*warm, i > 0, "point {i}");
        // no step of this short line needs halving (the halved case: the next test)
        assert_eq!((*steps, *failed_attempts), (1, 0), "point {i}");
        assert!(wall_seconds.is_finite() && *wall_seconds > 0.0, "point {i}: wall {wall_seconds}");
        let s = plan.scene_at(&[v]).unwrap();
        let opts = bvp::scene::BvpRunOptions::from_scene(&s).unwrap();
        let cold = bvp::scene::solve_scene(&s, &opts).unwrap().summary.scalars();
        assert_eq!(cold.len(), summary.len(), "point {i}: the same scalars");
        for ((name, a), (_, b)) in summary.iter().zip(&cold) {
            let scale = a.abs().max(b.abs()).max(1e-3);
            // the smallest pressure is an extremum of p, which the law computes from the
            // solution's derivatives: 1e-7 (measured 1.4e-8 at b₂ = 4e3)
            let tol = if name.ends_with("pressure_min") { 1e-7 } else { 1e-8 };
            assert!((a - b).abs() <= tol * scale, "b₂ = {v}: {name} warm {a} vs cold {b}");
        }
    }
}

/// A step too long for the warm start is halved, and the point says what that cost: on
/// `cosserat-drive`, ω₁ = 20 → 120 rad/s in one step fails from the warm start and
/// solves in two halves (measured: 2 steps, 1 failed attempt); the point's wall time
/// covers the failed attempt, and its summary is that of a cold solve at ω₁ = 120 to
/// the solver tolerance (as in the test above). A failed solve that went uncounted, or a
/// halving that returned the unfinished intermediate point, fails here.
#[test]
fn a_halved_step_counts_its_failed_attempt() {
    let scene = cosserat_drive();
    let range: ParamRange = "drive.driver_speed=20:120:2".parse().unwrap();
    let mut plan = SweepPlan::new(&scene, vec![range], 0).unwrap();
    plan.asymptotes = false;
    let sweep = Sweep::run(&scene, &plan, &|_| {});
    assert!(sweep.failures().is_empty(), "{:?}", sweep.failures());
    let PointStatus::Solved { summary, warm, steps, failed_attempts, wall_seconds, .. } = &sweep.lines[0].points[1].status else { panic!("{:?}", sweep.lines[0].points[1].status) };
    assert!(*warm && *steps >= 2 && *failed_attempts >= 1, "warm {warm}, {steps} steps, {failed_attempts} failed");
    assert!(wall_seconds.is_finite() && *wall_seconds > 0.0);
    let s = plan.scene_at(&[120.0]).unwrap();
    let cold = bvp::scene::solve_scene(&s, &bvp::scene::BvpRunOptions::from_scene(&s).unwrap()).unwrap().summary.scalars();
    for ((name, a), (_, b)) in summary.iter().zip(&cold) {
        let scale = a.abs().max(b.abs()).max(1e-3);
        let tol = if name.ends_with("pressure_min") { 1e-7 } else { 1e-8 };
        assert!((a - b).abs() <= tol * scale, "{name}: halved {a} vs cold {b}");
    }
}

/// Points no solve reaches report what their attempts cost: `string-drive` loaded with
/// 30 and 40 N·m (above its friction capacity of ≈ 16 N·m, see the next test) — the
/// first point's cold solve fails, the second is tried cold only (after a failure):
/// each `failed` with ≥ 1 failed attempt and its wall time, in the JSON and the table.
#[test]
fn failed_points_report_their_attempts() {
    let dir = temp("failed-points");
    let o = beltcheck(&["sweep", "scenes/string-drive.json", "--param", "drive.driven_torque=30:40:2", "--fe-points", "0", "-o", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}\n{}", stdout(&o), stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.join("sweep.json")).unwrap()).unwrap();
    for p in v["lines"][0]["points"].as_array().unwrap() {
        assert_eq!(p["status"], "failed", "{p}");
        assert!(p["failed_attempts"].as_u64().unwrap() >= 1, "{p}");
        assert!(p["wall_seconds"].as_f64().unwrap() > 0.0, "{p}");
    }
    assert!(std::fs::read_to_string(dir.join("sweep.md")).unwrap().contains("| failed | (1 failed) |"));
}

/// Bad parameters are named errors with exit status 2 before anything runs; nothing is
/// written.
#[test]
fn bad_parameters_are_refused_and_nothing_is_written() {
    let dir = temp("refused");
    let cases = [
        ("belt.shear_stifness=1:2:3", "has no `shear_stifness`"),
        ("belt.theory=1:2:3", "is the string \"cosserat\", not a number"),
        ("belt.shear_stiffness=1e2:1e6:log:1", "at least 2 points"),
        ("belt.shear_stiffness=0:1e6:log:5", "log range needs positive bounds"),
        ("belt.shear_stiffness=1e2:1e2:5", "an empty range"),
        ("belt.shear_stiffness", "no `=`"),
        ("belt.shear_stiffness=1e2:1e6:lin:5", "`lin` where `log` or nothing is expected"),
    ];
    for (param, message) in cases {
        let o = beltcheck(&["sweep", "scenes/cosserat-drive.json", "--param", param, "-o", dir.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2), "{param}: {}", stderr(&o));
        assert!(stderr(&o).contains(message), "{param}: {}", stderr(&o));
        assert!(!dir.exists(), "{param}: nothing written");
    }
}

/// A sweep of the load torque past the friction capacity of the `string-drive` scene
/// (about 16 N·m: the stick arc of the driven pulley vanishes): the points beyond it
/// have no steady solution (each named with the error, or the line stopped where the
/// continuation turned, with the reason), the report is still written and names them,
/// exit status 2.
#[test]
fn points_without_a_solution_give_exit_status_2() {
    let dir = temp("capacity");
    let o = beltcheck(&["sweep", "scenes/string-drive.json", "--param", "drive.driven_torque=10:40:4", "--fe-points", "0", "-o", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}\n{}", stdout(&o), stderr(&o));
    let err = stderr(&o);
    // either each point beyond the capacity failed with its error, or the line stopped
    // where the continuation could not pass, with the reason
    let named = err.contains("drive.driven_torque = 40: no steady solution") || (err.contains("fold/no solution beyond drive.driven_torque") && err.contains("stick arc"));
    assert!(err.contains("without a solution") && named, "{err}");
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.join("sweep.json")).unwrap()).unwrap();
    let points = v["lines"][0]["points"].as_array().unwrap();
    assert_eq!(points[0]["status"], "solved");
    assert_ne!(points[3]["status"], "solved");
    assert!(std::fs::read_to_string(dir.join("sweep.md")).unwrap().contains("Points without a solution"));
}
