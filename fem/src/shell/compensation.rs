//! The compensating swivel (spec E-5; issue 15): the constant swivel β_y* of the
//! steering drum that cancels the run-off of a cambered belt — how a controller holds a
//! belt whose camber it cannot change (docs/fem-shell.md §14 "The compensating swivel").
//!
//! v(β) is the scene's run-off velocity ([`super::scene::solve`], summary
//! `runoff_velocity`) with the steering drum's swivel history replaced by the constant β
//! (ramped at rest like any tilt; the scene's `tilt_x` history and camber kept). For small
//! imperfections v is linear in β (E-5; on the CI belt v(2β)/v(β) = 1.9996 at β = 1e-6
//! rad), but a probe β₁ large enough to slacken a belt edge is not (1.88 at 2.5e-4 rad):
//! so three solves give the estimate — v(0), v(β₁) and the secant's v at
//! β_a = −β₁ v(0)/(v(β₁) − v(0)), then β_lin = −β_a v(0)/(v(β_a) − v(0)) —, the root is
//! bracketed around β_lin and found by Brent's method ([`numerics::roots::brent`]) to
//! [`RELATIVE_TOLERANCE`] of |β_lin|, each evaluation one whole solve. The result states
//! v(0), the probe, the estimate, the root and the run-off left there.

use drive::scene::{Scene, Steering, SteeringDrum};
use serde::Serialize;

use super::scene::{solve, ShellScene};
use super::ShellError;

/// Brent's tolerance on β_y*, relative to the linear estimate |β_lin|.
pub const RELATIVE_TOLERANCE: f64 = 1e-4;

/// The swivel of the probe solve when the scene's steering drum has no swivel history, rad
/// (small enough for the linear range of a steel belt: docs/fem-shell.md §9.3).
pub const DEFAULT_PROBE: f64 = 5e-4;

/// A compensating swivel and how it was found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Compensation {
    /// The steered drum.
    pub drum: SteeringDrum,
    /// β_y*, rad: the constant swivel that cancels the run-off.
    pub swivel: f64,
    /// v(0), m/s: the run-off without swivel.
    pub runoff_without: f64,
    /// [β₁, v(β₁)] of the probe solve (rad, m/s).
    pub probe: [f64; 2],
    /// The secant estimate −β_a v(0)/(v(β_a) − v(0)) at β_a = −β₁ v(0)/(v(β₁) − v(0)),
    /// rad: the linear estimate the root is bracketed around.
    pub linear_estimate: f64,
    /// v(β_y*), m/s: the run-off left at the root (its size against v(0) measures how
    /// well the root was found).
    pub runoff_left: f64,
    /// Brent's absolute tolerance on β_y*, rad.
    pub tolerance: f64,
    /// Whole solves made.
    pub solves: usize,
}

/// The scene with the steering drum's swivel held at β from t = 0.
fn with_swivel(scene: &Scene, drum: SteeringDrum, beta: f64) -> Scene {
    let mut s = scene.clone();
    let tilt_x = scene.drive.steering.as_ref().map(|st| st.tilt_x.clone()).unwrap_or_default();
    s.drive.steering = Some(Steering { drum, tilt_x, tilt_y: vec![[0.0, beta]] });
    s
}

/// The compensating swivel of a cambered belt (module documentation).
///
/// # Errors
/// [`ShellError::NotModelled`]: a scene without camber or whose drums do not turn (no
/// run-off to cancel), or a swivel that does not move the run-off; the solves' errors;
/// [`ShellError::Check`]: no root near the linear estimate (v not monotone there).
pub fn compensating_swivel(scene: &Scene) -> Result<Compensation, ShellError> {
    let data = ShellScene::from_scene(scene)?;
    if !data.turning {
        return Err(ShellError::NotModelled("a compensating swivel needs turning drums (a transient with ω > 0): at rest nothing runs off".into()));
    }
    if data.camber == 0.0 {
        return Err(ShellError::NotModelled("a compensating swivel needs a camber to compensate (`belt.camber`)".into()));
    }
    let drum = scene.drive.steering.as_ref().map_or(SteeringDrum::Driven, |s| s.drum);
    let history = scene.drive.steering.as_ref().map(|s| s.tilt_y.as_slice()).unwrap_or(&[]);
    let largest = history.iter().fold(0.0_f64, |m, p| m.max(p[1].abs()));
    let probe = if largest > 0.0 { largest } else { DEFAULT_PROBE };
    let solves = std::cell::Cell::new(0);
    let mut seen: Vec<(f64, f64)> = Vec::new();
    let mut velocity = |beta: f64| -> Result<f64, ShellError> {
        if let Some(&(_, v)) = seen.iter().find(|(b, _)| *b == beta) {
            return Ok(v);
        }
        solves.set(solves.get() + 1);
        let solved = solve(&with_swivel(scene, drum, beta))?;
        let v = solved.summary.runoff_velocity.ok_or_else(|| ShellError::Check(format!("no run-off velocity at the swivel {beta:e} rad")))?;
        seen.push((beta, v));
        Ok(v)
    };
    let v0 = velocity(0.0)?;
    let v1 = velocity(probe)?;
    let slope = (v1 - v0) / probe;
    if !(slope.is_finite() && slope != 0.0) {
        return Err(ShellError::NotModelled(format!("the swivel does not steer the belt: v(0) = {v0:e} m/s, v({probe:e} rad) = {v1:e} m/s")));
    }
    // the secant through v(0) and v(β_lin): the probe may lie outside the linear range
    // (a swivel that slackens a belt edge: docs/fem-shell.md §14), β_lin does not
    let first = -v0 / slope;
    let v_first = velocity(first)?;
    let secant = (v_first - v0) / first;
    if !(secant.is_finite() && secant != 0.0) {
        return Err(ShellError::NotModelled(format!("the swivel does not steer the belt near {first:e} rad: v(0) = {v0:e} m/s, v({first:e} rad) = {v_first:e} m/s")));
    }
    let estimate = -v0 / secant;
    let tolerance = (RELATIVE_TOLERANCE * estimate.abs()).max(1e-12);
    // the bracket: ±2 % of the estimate (linear to ~1e-4 relative), widened ×4 twice
    let mut root = None;
    for width in [0.02, 0.08, 0.32] {
        let half = width * estimate.abs();
        match numerics::roots::brent(&mut velocity, estimate - half, estimate + half, tolerance) {
            Ok(x) => {
                root = Some(x);
                break;
            }
            Err(numerics::roots::RootError::NotBracketed { .. }) => continue,
            Err(numerics::roots::RootError::Evaluation(e)) => return Err(e),
            Err(e) => return Err(ShellError::Check(format!("the compensating swivel: {e}"))),
        }
    }
    let swivel = root.ok_or_else(|| {
        ShellError::Check(format!("no compensating swivel within ±32 % of the linear estimate {estimate:e} rad (v(0) = {v0:e}, v({probe:e}) = {v1:e} m/s): the run-off is not linear in the swivel here"))
    })?;
    let runoff_left = velocity(swivel)?;
    Ok(Compensation { drum, swivel, runoff_without: v0, probe: [probe, v1], linear_estimate: estimate, runoff_left, tolerance, solves: solves.get() })
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    /// E-5 on the shipped belt (camber ΔL = 1e-5 m, swivel history up to 5e-4 rad) at
    /// 32 × 2 over 4 steps: the run-off left at the root is below 1e-3 of the camber's
    /// own (Brent's tolerance, 1e-4 of β*, times the slope bounds it at ~1e-4 of v(0));
    /// the root agrees with the secant estimate to 1e-2 (the run-off is linear in small
    /// swivels to ~1e-3; the probe's own estimate, at the scene's 5e-4 rad where an edge
    /// slackens, was 10 % off); the probe is the scene's largest swivel; a scene without
    /// camber is refused by name.
    #[test]
    fn compensating_swivel_cancels_the_camber_run_off() {
        let mut v: serde_json::Value = serde_json::from_str(include_str!("../../../scenes/shell-runoff.json")).unwrap();
        v["fem"] = json!({"elements_sigma": 32, "elements_zeta": 2, "steps": 4, "ramp_steps": 1});
        let scene = Scene::from_json_str(&v.to_string()).unwrap();
        let c = compensating_swivel(&scene).unwrap();
        eprintln!("{c:?}");
        assert_eq!(c.drum, SteeringDrum::Driven);
        assert_eq!(c.probe[0], 5e-4);
        assert!(c.runoff_without.abs() > 1e-8, "{c:?}");
        assert!(c.runoff_left.abs() <= 1e-3 * c.runoff_without.abs(), "{c:?}");
        assert!((c.swivel - c.linear_estimate).abs() <= 1e-2 * c.linear_estimate.abs(), "{c:?}");
        let mut w = v.clone();
        w["belt"].as_object_mut().unwrap().remove("camber");
        match compensating_swivel(&Scene::from_json_str(&w.to_string()).unwrap()) {
            Err(ShellError::NotModelled(m)) => assert!(m.contains("camber"), "{m}"),
            other => panic!("no camber: {other:?}"),
        }
    }
}
