//! The drift of a signal that settles by a damped oscillation: the least-squares fit of
//!
//!   y(t) ≈ a + v (t − t_e) + e^{−λ(t − t_e)} (B cos Ω(t − t_e) + C sin Ω(t − t_e)),
//!
//! t_e the last sample's time, over samples (t_k, y_k). v is the drift the signal keeps
//! once the oscillation has died out (the shell's lateral run-off after its transient,
//! docs/fem-shell.md §14 "The run-off after the transient").
//!
//! **Variable projection.** For fixed (λ, Ω) the model is linear in (a, v, B, C): a
//! least-squares solve (faer's column-pivoted QR, each column scaled to unit largest
//! entry so that e^{λ(t_e − t)} of a fast decay does not swamp the others). The residual
//! of that solve is a function of (λ, Ω) alone, minimised over the box λW ∈ [−4, 24],
//! 2π/Ω ∈ [max(W/24, 8 δt), 4W] (W the window, δt the mean sample spacing: a period
//! shorter than eight samples is not resolved, one longer than four windows is a slope)
//! — first on a grid (48 periods, log-spaced, × 10 decays), then by Nelder–Mead (argmin)
//! from the grid's best point in the scaled coordinates (λW, ln ΩW). λ < 0 is allowed
//! so that a growing oscillation is found and named by the caller, not fitted as a
//! decay.
//!
//! The fit is a model of the signal, not a proof of it: the caller judges it (two
//! windows agreeing, the window holding a period; `fem::shell::runoff::settled_runoff`).

use argmin::core::{CostFunction, Executor, State};
use argmin::solver::neldermead::NelderMead;
use faer::linalg::solvers::SolveLstsq;
use faer::Mat;

/// The fitted model of the module docs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DampedDrift {
    /// v, the drift (units of y per unit of t).
    pub velocity: f64,
    /// a, the drift line's value at t_e.
    pub offset: f64,
    /// λ, the oscillation's decay rate (1/t; negative: it grows).
    pub decay: f64,
    /// Ω, its angular frequency (rad per unit of t).
    pub angular_frequency: f64,
    /// √(B² + C²), the oscillation's amplitude at t_e.
    pub amplitude: f64,
    /// Root mean square of the residual.
    pub rms: f64,
}

impl DampedDrift {
    /// The oscillation's period 2π/Ω.
    pub fn period(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.angular_frequency
    }
}

/// Fewest samples [`fit_damped_drift`] fits (four linear and two nonlinear parameters,
/// and room for a residual).
pub const MIN_SAMPLES: usize = 12;

/// The fit of the module docs over the samples `(time, y)` (time increasing); `None`
/// with fewer than [`MIN_SAMPLES`] samples, times not increasing, a non-finite value,
/// or no finite least-squares solution.
pub fn fit_damped_drift(time: &[f64], y: &[f64]) -> Option<DampedDrift> {
    let n = time.len().min(y.len());
    if n < MIN_SAMPLES || time.windows(2).any(|w| !(w[1] > w[0])) || y[..n].iter().chain(&time[..n]).any(|v| !v.is_finite()) {
        return None;
    }
    let (t, y) = (&time[..n], &y[..n]);
    let width = t[n - 1] - t[0];
    let spacing = width / (n - 1) as f64;
    // y scaled to O(1) so that the cost's scale does not depend on the signal's units
    let (lo, hi) = y.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    let scale = if hi > lo { hi - lo } else { 1.0 };
    let problem = Projection { t, y, scale, width };
    let period = |min: f64, max: f64, i: usize, k: usize| min * (max / min).powf(i as f64 / (k - 1) as f64);
    let (p_min, p_max) = ((width / 24.0).max(8.0 * spacing), 4.0 * width);
    if p_min >= p_max {
        return None;
    }
    let bounds = Bounds { decay: (-4.0, 24.0), frequency: ((std::f64::consts::TAU / p_max * width).ln(), (std::f64::consts::TAU / p_min * width).ln()) };
    let mut best: Option<(f64, [f64; 2])> = None;
    for i in 0..48 {
        let w = (std::f64::consts::TAU / period(p_min, p_max, i, 48) * width).ln();
        for d in [-2.0, -0.5, 0.0, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 24.0] {
            if let Some(c) = problem.residual([d, w]) {
                if best.is_none_or(|(b, _)| c < b) {
                    best = Some((c, [d, w]));
                }
            }
        }
    }
    let (_, start) = best?;
    let simplex = vec![start.to_vec(), vec![start[0] + 0.5, start[1]], vec![start[0], start[1] + 0.1]];
    let solver = NelderMead::new(simplex).with_sd_tolerance(1e-30).ok()?;
    let cost = Bounded { problem: &problem, bounds };
    let x = match Executor::new(cost, solver).configure(|s| s.max_iters(400)).run() {
        Ok(res) => res.state().get_best_param().cloned().unwrap_or_else(|| start.to_vec()),
        Err(_) => start.to_vec(),
    };
    let x = [x[0], x[1]];
    let x = if bounds.contains(x) && problem.residual(x).is_some() { x } else { start };
    problem.fit(x)
}

/// The box of the scaled nonlinear parameters (λW, ln ΩW).
#[derive(Debug, Clone, Copy)]
struct Bounds {
    decay: (f64, f64),
    frequency: (f64, f64),
}

impl Bounds {
    fn contains(&self, x: [f64; 2]) -> bool {
        (self.decay.0..=self.decay.1).contains(&x[0]) && (self.frequency.0..=self.frequency.1).contains(&x[1])
    }
}

/// The samples and the linear solve for given (λW, ln ΩW).
struct Projection<'a> {
    t: &'a [f64],
    y: &'a [f64],
    scale: f64,
    width: f64,
}

impl Projection<'_> {
    /// The scaled columns and their scales at x = (λW, ln ΩW).
    fn columns(&self, x: [f64; 2]) -> (Mat<f64>, [f64; 4]) {
        let (decay, omega) = (x[0] / self.width, x[1].exp() / self.width);
        let te = self.t[self.t.len() - 1];
        let value = |k: usize, j: usize| {
            let s = self.t[k] - te;
            match j {
                0 => 1.0,
                1 => s / self.width,
                2 => (-decay * s).exp() * (omega * s).cos(),
                _ => (-decay * s).exp() * (omega * s).sin(),
            }
        };
        let mut scales = [0.0_f64; 4];
        for (j, m) in scales.iter_mut().enumerate() {
            *m = (0..self.t.len()).fold(0.0_f64, |m, k| m.max(value(k, j).abs()));
            if *m == 0.0 {
                *m = 1.0;
            }
        }
        (Mat::from_fn(self.t.len(), 4, |k, j| value(k, j) / scales[j]), scales)
    }

    /// The coefficients (a, v W, B, C) of the scaled signal, or `None` if not finite.
    fn coefficients(&self, x: [f64; 2]) -> Option<([f64; 4], f64)> {
        let (a, scales) = self.columns(x);
        let rhs = Mat::from_fn(self.y.len(), 1, |k, _| self.y[k] / self.scale);
        let c = a.col_piv_qr().solve_lstsq(&rhs);
        let coef = [c[(0, 0)] / scales[0], c[(1, 0)] / scales[1], c[(2, 0)] / scales[2], c[(3, 0)] / scales[3]];
        let fitted = &a * &c;
        let sum: f64 = (0..self.y.len()).map(|k| (fitted[(k, 0)] - rhs[(k, 0)]).powi(2)).sum();
        (coef.iter().all(|v| v.is_finite()) && sum.is_finite()).then_some((coef, sum))
    }

    /// The mean squared residual of the scaled signal at x.
    fn residual(&self, x: [f64; 2]) -> Option<f64> {
        self.coefficients(x).map(|(_, sum)| sum / self.y.len() as f64)
    }

    /// The fit at x in the caller's units.
    fn fit(&self, x: [f64; 2]) -> Option<DampedDrift> {
        let (c, sum) = self.coefficients(x)?;
        Some(DampedDrift {
            velocity: c[1] * self.scale / self.width,
            offset: c[0] * self.scale,
            decay: x[0] / self.width,
            angular_frequency: x[1].exp() / self.width,
            amplitude: c[2].hypot(c[3]) * self.scale,
            rms: (sum / self.y.len() as f64).sqrt() * self.scale,
        })
    }
}

/// The projected residual as argmin's cost, infinite outside the box.
struct Bounded<'a, 'b> {
    problem: &'a Projection<'b>,
    bounds: Bounds,
}

impl CostFunction for Bounded<'_, '_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, x: &Vec<f64>) -> Result<f64, argmin::core::Error> {
        let x = [x[0], x[1]];
        Ok(if self.bounds.contains(x) { self.problem.residual(x).unwrap_or(f64::INFINITY) } else { f64::INFINITY })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn signal(t: &[f64], a: f64, v: f64, decay: f64, omega: f64, b: f64, c: f64) -> Vec<f64> {
        let te = t[t.len() - 1];
        t.iter().map(|&t| a + v * (t - te) + (-decay * (t - te)).exp() * (b * (omega * (t - te)).cos() + c * (omega * (t - te)).sin())).collect()
    }

    /// A drift under a decaying oscillation of the size the shell shows (the 128 × 4
    /// run's last half: v = 1.25e-6 m/s under an oscillation of 1.2e-6 m at the end,
    /// period 24.4 s, decay 0.043 1/s, 49 s of samples every 0.049 s): v, λ, Ω and the
    /// amplitude come back to 1e-6 relative (exact data; the minimiser's tolerance).
    #[test]
    fn a_drift_under_a_decaying_oscillation_is_recovered() {
        let t: Vec<f64> = (0..1000).map(|k| 50.0 + 0.049 * k as f64).collect();
        let omega = std::f64::consts::TAU / 24.4;
        let y = signal(&t, 1.37e-4, 1.25e-6, 0.043, omega, 8e-7, -9e-7);
        let f = fit_damped_drift(&t, &y).unwrap();
        assert!((f.velocity / 1.25e-6 - 1.0).abs() < 1e-6, "{f:?}");
        assert!((f.decay / 0.043 - 1.0).abs() < 1e-5 && (f.angular_frequency / omega - 1.0).abs() < 1e-6, "{f:?}");
        assert!((f.amplitude / 8e-7f64.hypot(9e-7) - 1.0).abs() < 1e-5 && f.rms < 1e-12, "{f:?}");
        // a growing oscillation is fitted as one (λ < 0), not as a decay
        let y = signal(&t, 0.0, 1e-6, -0.01, omega, 1e-6, 0.0);
        let f = fit_damped_drift(&t, &y).unwrap();
        assert!((f.decay + 0.01).abs() < 1e-6 && (f.velocity / 1e-6 - 1.0).abs() < 1e-6, "{f:?}");
    }

    /// A straight line is its own drift (the oscillation's amplitude round-off), also
    /// with noise of 1e-3 of its rise on it; a constant drifts at 0.
    #[test]
    fn a_line_is_its_own_drift() {
        let t: Vec<f64> = (0..400).map(|k| 0.1 * k as f64).collect();
        let y: Vec<f64> = t.iter().map(|&t| 2.0 - 3e-6 * t).collect();
        let f = fit_damped_drift(&t, &y).unwrap();
        assert!((f.velocity + 3e-6).abs() < 1e-15 && f.amplitude < 1e-12, "{f:?}");
        let rise = 3e-6 * 40.0;
        let noisy: Vec<f64> = y.iter().enumerate().map(|(k, v)| v + 1e-3 * rise * ((k * 7919 % 101) as f64 / 50.0 - 1.0)).collect();
        let f = fit_damped_drift(&t, &noisy).unwrap();
        assert!((f.velocity + 3e-6).abs() < 1e-2 * 3e-6, "{f:?}");
        let f = fit_damped_drift(&t, &vec![5.0; t.len()]).unwrap();
        assert!(f.velocity.abs() < 1e-15, "{f:?}");
    }

    /// Too few samples, times not increasing or a NaN: no fit.
    #[test]
    fn bad_samples_are_not_fitted() {
        let t: Vec<f64> = (0..MIN_SAMPLES - 1).map(|k| k as f64).collect();
        assert!(fit_damped_drift(&t, &t).is_none());
        let mut t: Vec<f64> = (0..40).map(|k| k as f64).collect();
        let mut y = t.clone();
        y[3] = f64::NAN;
        assert!(fit_damped_drift(&t, &y).is_none());
        t[5] = t[4];
        assert!(fit_damped_drift(&t, &t.clone()).is_none());
    }
}
