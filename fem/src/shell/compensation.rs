//! The compensating swivel (spec E-5; issue 15): the constant swivel β_y* of the
//! steering drum that cancels the run-off of a cambered belt — how a controller holds a
//! belt whose camber it cannot change (docs/fem-shell.md §14 "The compensating swivel").
//!
//! v(β) is the scene's run-off velocity ([`super::scene::solve`]) with the steering drum's
//! swivel history replaced by the constant β (ramped at rest like any tilt; the scene's
//! `tilt_x` history and camber kept), measured as [`RunoffMeasure`] says: the run-off after
//! the lateral transient (summary `settled_runoff_velocity`) when the run without swivel
//! is long enough for it to settle — the drift a steering controller holds —, else the
//! slope over the last revolution (`runoff_velocity`), which in a run shorter than the
//! transient is a phase of it (docs/fem-shell.md §14), and the result says which. For small
//! imperfections v is linear in β (E-5; on the CI belt v(2β)/v(β) = 1.9996 at β = 1e-6
//! rad), but not in a probe large enough to change the span's stress from edge to edge by
//! 40 % of its mean (1.88 at 2.5e-4 rad; docs/fem-shell.md §14), and
//! the summary's slope over a short run of the CI scene is far from linear, and on coarse
//! meshes v(β) jumps where a large swivel switches a clip or a contact edge (at |β| ≈
//! 3.8e-4 rad on 32 × 2 with one step of 2·π/32; docs/fem-shell.md §9.4): so the probe
//! β₁ lies in the linear range ([`LINEAR_PROBE`], or the scene's largest swivel if
//! smaller), v(0) and v(β₁) give the linear estimate β_lin = −β₁ v(0)/(v(β₁) − v(0)),
//! secant steps through the last two points go outward from there until two points
//! bracket a sign change (at most [`MAX_SECANT_STEPS`], within |β| < π/4), and Brent's method
//! ([`numerics::roots::brent`]) finds the root in the bracket to [`RELATIVE_TOLERANCE`]
//! of its larger end, each evaluation one whole solve. The result states v(0), the probe,
//! the estimate, the root and the run-off left there.

use drive::result::TimeSeries;
use drive::scene::{Scene, Steering, SteeringDrum};
use serde::Serialize;

use super::scene::{solve, ShellScene};
use super::ShellError;

/// Brent's tolerance on β_y*, relative to the larger end of its bracket.
pub const RELATIVE_TOLERANCE: f64 = 1e-4;

/// The largest |v(β_y*)| accepted, relative to |v(0)|: Brent's tolerance leaves ~1e-4
/// of it on a continuous v; more means v jumps across the bracket (a discontinuous
/// run-off, e.g. a short run's slope window), and no swivel cancels it — an error.
pub const LEFT_TOLERANCE: f64 = 1e-2;

/// Secant steps allowed to find two swivels whose run-offs bracket the root.
pub const MAX_SECANT_STEPS: usize = 6;

/// The largest swivel of the probe solve, rad: inside the linear range, so that the
/// linear estimate from v(0) and v(β₁) is close to the root and the secant walks outward
/// to it before it meets a jump of v(β). On the shipped belt at 32 × 2 over 4 steps v/β
/// is 3.028e-3 and 3.061e-3 m/s per rad at 2e-5 and 2e-4 rad (1 %), but 4.81e-3 at 5e-4
/// rad, the scene's own swivel (docs/fem-shell.md §14 "Small means small"); and 5e-5 rad
/// still moves the run-off by 1.5e-7 m/s there (4e-7 m/s settled over ten
/// revolutions at 128 × 8), far above the spread of the settled fits (≤ 2e-8 m/s, §14).
pub const LINEAR_PROBE: f64 = 5e-5;

/// Which run-off the compensating swivel cancels: chosen by the run without swivel and
/// kept for every solve of the search, so that v(β) is one function of β.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RunoffMeasure {
    /// The run-off after the lateral transient (`settled_runoff_velocity`): the run
    /// without swivel settled. A solve of the search that does not settle is an error.
    Settled,
    /// The least-squares slope over the last revolution (`runoff_velocity`): the run
    /// without swivel did not settle (too short for the transient, or its fits refused;
    /// it warns why), and the root cancels this slope, not the drift after the transient.
    LastRevolution,
}

impl RunoffMeasure {
    /// The summary's name of the velocity this measure reads.
    pub fn summary_name(self) -> &'static str {
        match self {
            RunoffMeasure::Settled => "settled_runoff_velocity",
            RunoffMeasure::LastRevolution => "runoff_velocity",
        }
    }

    /// The measure the run without swivel calls for and its run-off v(0):
    /// [`Self::Settled`] with `settled` (`settled_runoff_velocity`) when it exists, else
    /// [`Self::LastRevolution`] with `slope` (`runoff_velocity`).
    ///
    /// # Errors
    /// [`ShellError::Check`] naming both summary names when the run has neither.
    pub fn of_first_run(settled: Option<f64>, slope: Option<f64>) -> Result<(RunoffMeasure, f64), ShellError> {
        match (settled, slope) {
            (Some(v), _) => Ok((RunoffMeasure::Settled, v)),
            (None, Some(v)) => Ok((RunoffMeasure::LastRevolution, v)),
            (None, None) => Err(ShellError::Check(
                "the run without swivel has no settled_runoff_velocity and no runoff_velocity: no run-off to cancel".into(),
            )),
        }
    }
}

/// The run-off of a later solve of the search, at the swivel `beta`, under the `measure`
/// of the run without swivel whose run-off was `v0`: the last revolution's `slope`, or the
/// settled run-off of `history` with its two fit windows held to
/// [`crate::shell::runoff::SETTLED_AGREEMENT`] of |v0| (near the root a solve's own run-off
/// is ~0, and 2 % of that no fit can meet; [`super::scene::settled_of`]).
///
/// # Errors
/// [`ShellError::Check`] naming the swivel: a run without the slope, or under the settled
/// measure a run whose run-off did not settle (never a silent switch to the slope).
fn later_runoff(measure: RunoffMeasure, v0: f64, data: &ShellScene, history: &TimeSeries, slope: Option<f64>, beta: f64) -> Result<f64, ShellError> {
    match measure {
        RunoffMeasure::LastRevolution => slope.ok_or_else(|| ShellError::Check(format!("no runoff_velocity at the swivel {beta:e} rad"))),
        RunoffMeasure::Settled => super::scene::settled_of(data, history, crate::shell::runoff::SETTLED_AGREEMENT * v0.abs())
            .map(|s| s.velocity)
            .map_err(|why| {
                ShellError::Check(format!(
                    "the run-off at the swivel {beta:e} rad did not settle (the run without swivel did, at {v0:e} m/s, so the search cancels the settled run-off): {why}"
                ))
            }),
    }
}

/// A compensating swivel and how it was found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Compensation {
    /// The steered drum.
    pub drum: SteeringDrum,
    /// The run-off cancelled: `settled` (after the lateral transient) or
    /// `last_revolution` (the slope of a run too short to settle).
    pub measure: RunoffMeasure,
    /// β_y*, rad: the constant swivel that cancels the run-off.
    pub swivel: f64,
    /// v(0), m/s: the run-off without swivel.
    pub runoff_without: f64,
    /// [β₁, v(β₁)] of the probe solve (rad, m/s).
    pub probe: [f64; 2],
    /// β_lin = −β₁ v(0)/(v(β₁) − v(0)), rad: the linear estimate from v(0) and the probe.
    pub linear_estimate: f64,
    /// v(β_y*), m/s: the run-off left at the root (its size against v(0) measures how
    /// well the root was found).
    pub runoff_left: f64,
    /// Brent's absolute tolerance on β_y*, rad (1e-4 of the larger end of the bracket).
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
/// [`ShellError::Check`]: no sign change of the run-off within the secant steps, a secant
/// step outside the admissible tilts, Brent's method failing, a run-off that jumps across
/// its sign change (more than [`LEFT_TOLERANCE`] of v(0) left at Brent's end).
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
    let probe = if largest > 0.0 { largest.min(LINEAR_PROBE) } else { LINEAR_PROBE };
    let mut seen: Vec<(f64, f64)> = Vec::new();
    // the measure is the run without swivel's (the first solve), then kept; under the
    // settled measure the later runs' fits are held to 2 % of v(0), not of their own
    // run-off: near the root that is ~0, and a 2 % of it no fit can meet
    let mut measure: Option<(RunoffMeasure, f64)> = None;
    let mut velocity = |beta: f64| -> Result<f64, ShellError> {
        if let Some(&(_, v)) = seen.iter().find(|(b, _)| *b == beta) {
            return Ok(v);
        }
        let swivelled = with_swivel(scene, drum, beta);
        let solved = solve(&swivelled)?;
        let (settled, slope) = (solved.summary.settled_runoff_velocity, solved.summary.runoff_velocity);
        let v = match measure {
            None => {
                let (m, v) = RunoffMeasure::of_first_run(settled, slope)?;
                measure = Some((m, v));
                v
            }
            Some((m, v0)) => later_runoff(m, v0, &ShellScene::from_scene(&swivelled)?, &solved.history, slope, beta)?,
        };
        seen.push((beta, v));
        Ok(v)
    };
    let v0 = velocity(0.0)?;
    let v1 = velocity(probe)?;
    if !((v1 - v0) / probe).is_finite() || v1 == v0 {
        return Err(ShellError::NotModelled(format!("the swivel does not steer the belt: v(0) = {v0:e} m/s, v({probe:e} rad) = {v1:e} m/s")));
    }
    let estimate = -probe * v0 / (v1 - v0);
    // secant steps through the last two points until two points bracket the root (the
    // run-off is linear in small swivels, but the root may lie beyond the linear range,
    // and the summary's slope over a short run may be far from linear: the first
    // estimate can be 10× off), then Brent's method on the bracket
    let mut points = vec![(0.0, v0), (probe, v1)];
    let bracket = loop {
        let mut sorted = points.clone();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
        if let Some(w) = sorted.windows(2).find(|w| w[0].1 * w[1].1 <= 0.0) {
            break (w[0].0, w[1].0);
        }
        if points.len() >= 2 + MAX_SECANT_STEPS {
            return Err(ShellError::Check(format!(
                "no compensating swivel after {MAX_SECANT_STEPS} secant steps from v(0) = {v0:e} m/s, v({probe:e} rad) = {v1:e} m/s (last points {:?}): the run-off does not change sign",
                &points[points.len() - 2..]
            )));
        }
        let [(a, va), (b, vb)] = [points[points.len() - 2], points[points.len() - 1]];
        let next = b - vb * (b - a) / (vb - va);
        if !(next.is_finite() && next.abs() < drive::scene::MAX_TILT) {
            return Err(ShellError::Check(format!("the secant for the compensating swivel left the admissible tilts (|β| < π/4) at {next:e} rad from ({a:e}, {va:e}), ({b:e}, {vb:e})")));
        }
        points.push((next, velocity(next)?));
    };
    let tolerance = (RELATIVE_TOLERANCE * bracket.0.abs().max(bracket.1.abs())).max(1e-12);
    let swivel = numerics::roots::brent(&mut velocity, bracket.0, bracket.1, tolerance).map_err(|e| match e {
        numerics::roots::RootError::Evaluation(e) => e,
        e => ShellError::Check(format!("the compensating swivel: {e}")),
    })?;
    let runoff_left = velocity(swivel)?;
    if !(runoff_left.abs() <= LEFT_TOLERANCE * v0.abs()) {
        let mut near: Vec<(f64, f64)> = seen.iter().copied().filter(|p| p.0 != swivel).collect();
        near.sort_by(|a, b| (a.0 - swivel).abs().total_cmp(&(b.0 - swivel).abs()));
        return Err(ShellError::Check(format!(
            "no swivel cancels the run-off: Brent's method ended at β_y = {swivel:e} rad with a run-off of {runoff_left:e} m/s left ({:.2} of v(0) = {v0:e} m/s; allowed {LEFT_TOLERANCE:e}) — the run-off jumps there (nearest other swivels: {:?}), so it changes sign without passing 0",
            runoff_left / v0,
            &near[..near.len().min(2)]
        )));
    }
    let measure = measure.map_or(RunoffMeasure::LastRevolution, |(m, _)| m);
    Ok(Compensation { drum, measure, swivel, runoff_without: v0, probe: [probe, v1], linear_estimate: estimate, runoff_left, tolerance, solves: seen.len() })
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    /// Δt for ωΔt = π/16 at the shipped scene's ω = 2 rad/s.
    use crate::shell::scene::PI16_STEP as PI16;

    /// E-5 on the shipped belt (camber ΔL = 1e-5 m, swivel history up to 5e-4 rad) at
    /// 32 × 2 over 4 steps: the run-off left at the root is below 1e-3 of the camber's
    /// own (Brent's tolerance, 1e-4 of β*, times the slope bounds it at ~1e-4 of v(0));
    /// the probe is [`LINEAR_PROBE`], not the scene's 5e-4 rad, which lies outside the
    /// linear range (v(β)/v(β/2) = 1.88 there), and the linear estimate from it lies
    /// within 5 % of the root: v/β varies by 1 % between 2e-5 and 2e-4 rad and the cross
    /// term of camber and swivel is 0.4 % (docs/fem-shell.md §14), where the probe at 5e-4
    /// rad missed the root by 37 % (+1.400e-4 against +8.87e-5 rad); a smaller swivel in
    /// the scene is the probe itself, and the root does not depend on the probe beyond
    /// Brent's tolerance; a scene without camber is refused by name.
    #[test]
    fn compensating_swivel_cancels_the_camber_run_off() {
        let mut v: serde_json::Value = serde_json::from_str(include_str!("../../../scenes/shell-runoff.json")).unwrap();
        v["fem"] = json!({"elements_sigma": 32, "elements_zeta": 2, "steps": 4, "ramp_steps": 1, "time_step": PI16});
        let scene = Scene::from_json_str(&v.to_string()).unwrap();
        let c = compensating_swivel(&scene).unwrap();
        eprintln!("{c:?}");
        assert_eq!(c.drum, SteeringDrum::Driven);
        // 4 steps are far shorter than the lateral transient: the slope is cancelled
        assert_eq!(c.measure, RunoffMeasure::LastRevolution);
        assert_eq!(c.probe[0], LINEAR_PROBE);
        assert!(c.runoff_without.abs() > 1e-8, "{c:?}");
        assert!(c.runoff_left.abs() <= 1e-3 * c.runoff_without.abs(), "{c:?}");
        assert!((c.swivel / c.linear_estimate - 1.0).abs() < 0.05, "{c:?}");
        // a scene whose largest swivel is inside the linear range probes with it
        let mut small = v.clone();
        small["drive"]["steering"]["tilt_y"] = json!([[0.0, 0.0], [1.0, 2e-5]]);
        let d = compensating_swivel(&Scene::from_json_str(&small.to_string()).unwrap()).unwrap();
        assert_eq!(d.probe[0], 2e-5);
        assert!((d.swivel - c.swivel).abs() <= c.tolerance + d.tolerance, "{c:?} {d:?}");
        let mut w = v.clone();
        w["belt"].as_object_mut().unwrap().remove("camber");
        match compensating_swivel(&Scene::from_json_str(&w.to_string()).unwrap()) {
            Err(ShellError::NotModelled(m)) => assert!(m.contains("camber"), "{m}"),
            other => panic!("no camber: {other:?}"),
        }
    }

    /// The measure is chosen by the run without swivel and then held: a settled run reads
    /// the settled run-off (not the slope, which differs), a short run the slope; a solve
    /// of the search that does not settle under the settled measure is an error naming the
    /// swivel, never a silent switch to the slope.
    #[test]
    fn the_run_off_measure_is_the_run_without_swivels_and_is_held() {
        assert_eq!(RunoffMeasure::of_first_run(Some(1.2e-6), Some(1.4e-6)).unwrap(), (RunoffMeasure::Settled, 1.2e-6));
        assert_eq!(RunoffMeasure::of_first_run(None, Some(1.4e-6)).unwrap(), (RunoffMeasure::LastRevolution, 1.4e-6));
        match RunoffMeasure::of_first_run(None, None) {
            Err(ShellError::Check(m)) => assert!(m.contains("settled_runoff_velocity") && m.contains("runoff_velocity"), "{m}"),
            other => panic!("no run-off at all: {other:?}"),
        }
        // later solves on a synthetic history (a drift of 3e-8 m/s, 3 % of v0 = 1e-6:
        // near the root) under each measure
        let data = ShellScene::from_scene(&Scene::from_json_str(include_str!("../../../scenes/shell-runoff.json")).unwrap()).unwrap();
        let settling = super::super::scene::lateral_history(3e-8, 0.04);
        let v = later_runoff(RunoffMeasure::Settled, 1e-6, &data, &settling, Some(1.4e-6), 3e-4).unwrap();
        // the fit's model is the history's form: the drift to 1 %, not the slope 1.4e-6
        assert!((v - 3e-8).abs() < 1e-2 * 3e-8, "the settled drift, not the slope: {v:e}");
        assert_eq!(later_runoff(RunoffMeasure::LastRevolution, 1e-6, &data, &settling, Some(1.4e-6), 3e-4).unwrap(), 1.4e-6);
        // a growing oscillation never settles: under the settled measure an error that
        // names the swivel, though the slope exists
        let ringing = super::super::scene::lateral_history(3e-8, -0.02);
        match later_runoff(RunoffMeasure::Settled, 1e-6, &data, &ringing, Some(1.4e-6), 3e-4) {
            Err(ShellError::Check(m)) => assert!(m.contains("3e-4") && m.contains("did not settle"), "{m}"),
            other => panic!("an unsettled solve under the settled measure: {other:?}"),
        }
        match later_runoff(RunoffMeasure::LastRevolution, 1e-6, &data, &settling, None, 0.0) {
            Err(ShellError::Check(m)) => assert!(m.contains("runoff_velocity"), "{m}"),
            other => panic!("no slope: {other:?}"),
        }
        assert_eq!(serde_json::to_value(RunoffMeasure::LastRevolution).unwrap(), json!("last_revolution"));
        assert_eq!(serde_json::to_value(RunoffMeasure::Settled).unwrap(), json!("settled"));
    }
}
