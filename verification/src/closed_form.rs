//! Closed forms that serve as references ([`crate::reference::Reference::ClosedForm`]).
//!
//! # The elastic catenary loop (`string-hanging`, docs/string-hanging.md (S3), (S6))
//! An extensible string (EA, weight w = ρg per unstretched length) hangs on two equal
//! frictionless pulleys (radius R to the centreline, centres (∓H/2, 0)). Each span is an
//! elastic catenary; by the mirror symmetry of geometry and load its vertex lies at x = 0.
//! With the unstretched arc length s̃ from the vertex and the horizontal force F (N):
//!
//!   x(s̃) = F s̃/EA + (F/w) asinh(w s̃/F),
//!   y(s̃) = w s̃²/(2EA) + (F/w)(√(1 + (w s̃/F)²) − 1),   tan θ = w s̃/F,   T = √(F² + (w s̃)²).
//!
//! A span leaves a pulley tangentially: the upper span (half length s_u, angle θ_u at its
//! right end) touches the driven pulley at (H/2 − R sin θ_u, R cos θ_u), the lower span
//! (s_l, θ_l) at (H/2 + R sin θ_l, −R cos θ_l). On the frictionless arcs the invariant
//! E = T + T²/(2EA) − w y (DESIGN.md) carries the tension, so T(y) = EA(√(1 + 2(E + w y)/EA) − 1).
//! The unknowns (F_u, s_u, F_l, s_l) solve four equations:
//! 1. tangency of the upper span: x(s_u; F_u) = H/2 − R sin θ_u;
//! 2. tangency of the lower span: x(s_l; F_l) = H/2 + R sin θ_l;
//! 3. one invariant round the loop: E at the upper vertex = E at the lower vertex;
//! 4. the belt length: L = 2 s_u + 2 s_l + 2 ∫ R dφ / (1 + T(R sin φ)/EA) over the arc
//!    φ ∈ [−π/2 + θ_l, π/2 + θ_u] (each pulley carries the same arc).
//!
//! These are closed-form expressions in four numbers; the arc integral is composite
//! 5-point Gauss–Legendre (smooth integrand: 64 panels leave 1e-15), and the four
//! equations are solved by Newton to [`CATENARY_TOLERANCE`]. Nothing here calls the BVP:
//! it is an independent reference for the BVP and the FE alike.

use std::f64::consts::PI;

use drive::scene::{Analysis, Contact, Layout, Scene, Theory};
use drive::summary::{Global, PulleyId, PulleyQuantity, Quantity, Summary};

/// Relative tolerance of the four catenary equations: each residual below this times its
/// scale (H for lengths, the mid-span tension for forces).
pub const CATENARY_TOLERANCE: f64 = 1e-13;

/// Why a closed form gives no reference for a scene.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ClosedFormError {
    /// The closed form describes another model.
    #[error("the {form} closed form is for {model}; scene `{scene}` is {found}")]
    NotThisModel {
        /// Which closed form.
        form: &'static str,
        /// What it describes.
        model: &'static str,
        /// Scene name.
        scene: String,
        /// The scene's model in words.
        found: String,
    },
    /// Newton on the four equations did not converge.
    #[error("the elastic catenary equations did not converge: residual {residual:.3e} (relative) after {iterations} Newton iterations")]
    NotConverged {
        /// Largest scaled residual at the end.
        residual: f64,
        /// Iterations made.
        iterations: usize,
    },
}

/// The solved catenary loop: the two spans' horizontal forces and half lengths.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CatenaryLoop {
    /// R, m.
    pub radius: f64,
    /// H, m.
    pub centre_distance: f64,
    /// EA, N.
    pub axial_stiffness: f64,
    /// w = ρ g, N/m.
    pub weight: f64,
    /// F_u: horizontal force (= axial force at the vertex) of the upper span, N.
    pub force_upper: f64,
    /// s_u: unstretched half length of the upper span, m.
    pub half_upper: f64,
    /// F_l of the lower span, N.
    pub force_lower: f64,
    /// s_l of the lower span, m.
    pub half_lower: f64,
    /// Newton iterations used.
    pub iterations: usize,
}

/// (x, y) of the elastic catenary at s̃ from its vertex, horizontal force `f`.
fn shape(f: f64, w: f64, ea: f64, s: f64) -> (f64, f64) {
    let a = w * s / f;
    (f * s / ea + (f / w) * a.asinh(), w * s * s / (2.0 * ea) + (f / w) * ((1.0 + a * a).sqrt() - 1.0))
}

impl CatenaryLoop {
    /// Solves the loop of a `string-hanging` scene: two-pulley layout, theory `string`,
    /// analysis `static`, frictionless contact, gravity g > 0.
    ///
    /// # Errors
    /// [`ClosedFormError::NotThisModel`] for any other scene;
    /// [`ClosedFormError::NotConverged`] if Newton stalls (a belt so slack or so short
    /// that the parabolic start is far off).
    pub fn of_scene(scene: &Scene) -> Result<CatenaryLoop, ClosedFormError> {
        let g = scene.effects.gravity.unwrap_or(0.0);
        let fits = scene.drive.layout == Layout::TwoPulley
            && scene.belt.theory == Theory::String
            && scene.analysis == Analysis::Static
            && scene.effects.contact == Contact::Frictionless
            && g > 0.0;
        if !fits {
            return Err(ClosedFormError::NotThisModel {
                form: "elastic catenary",
                model: "a static string under gravity on two frictionless pulleys",
                scene: scene.name.clone(),
                found: format!(
                    "layout `{}`, theory `{}`, analysis `{}`, contact {:?}, gravity {g} m/s²",
                    scene.drive.layout, scene.belt.theory, scene.analysis, scene.effects.contact
                ),
            });
        }
        let d = &scene.drive;
        let b = &scene.belt;
        Self::solve(d.pulley_radius, d.centre_distance, b.length, b.axial_stiffness, b.mass_per_length * g)
    }

    /// Solves the four equations of the module docs for R, H, L, EA, w (SI).
    ///
    /// # Errors
    /// [`ClosedFormError::NotConverged`].
    pub fn solve(radius: f64, centre_distance: f64, length: f64, axial_stiffness: f64, weight: f64) -> Result<CatenaryLoop, ClosedFormError> {
        let (r, h, w) = (radius, centre_distance, weight);
        // Start: shallow inextensible parabolas sharing the slack equally,
        // ΔL_span = 8 f²/(3H), F = w H²/(8 f).
        let slack = (length - 2.0 * h - 2.0 * PI * r).max(1e-4 * h);
        let sag = (3.0 * h * 0.25 * slack / 8.0).sqrt().max(1e-3 * h);
        let f0 = w * h * h / (8.0 * sag);
        let mut u = [f0, 0.5 * h, f0, 0.5 * h];
        let mut lp = CatenaryLoop { radius, centre_distance, axial_stiffness, weight, force_upper: u[0], half_upper: u[1], force_lower: u[2], half_lower: u[3], iterations: 0 };
        let scale = [h, h, f0, h];
        let norm = |res: &[f64; 4]| res.iter().zip(&scale).map(|(x, s)| (x / s).abs()).fold(0.0, f64::max);
        let mut res = lp.with(u).residual(length);
        for it in 0..100 {
            if norm(&res) < CATENARY_TOLERANCE {
                lp.iterations = it;
                return Ok(lp);
            }
            // Jacobian by central differences (only the path to the root depends on it)
            let mut jac = [[0.0; 4]; 4];
            for k in 0..4 {
                let step = 1e-7 * u[k].abs().max(1e-12);
                let (mut up, mut dn) = (u, u);
                up[k] += step;
                dn[k] -= step;
                let (rp, rm) = (lp.with(up).residual(length), lp.with(dn).residual(length));
                for i in 0..4 {
                    jac[i][k] = (rp[i] - rm[i]) / (2.0 * step);
                }
            }
            let Some(du) = solve4(jac, res.map(|x| -x)) else { break };
            // damped: keep forces and half lengths positive, accept a decrease
            let mut t = 1.0;
            loop {
                let trial: [f64; 4] = std::array::from_fn(|k| u[k] + t * du[k]);
                if trial.iter().all(|&x| x > 0.0) {
                    let rt = lp.with(trial).residual(length);
                    if norm(&rt) < norm(&res) || t < 1e-6 {
                        u = trial;
                        res = rt;
                        break;
                    }
                }
                t *= 0.5;
                if t < 1e-6 {
                    break;
                }
            }
            lp = lp.with(u);
            lp.iterations = it + 1;
        }
        Err(ClosedFormError::NotConverged { residual: norm(&res), iterations: lp.iterations })
    }

    fn with(&self, u: [f64; 4]) -> CatenaryLoop {
        CatenaryLoop { force_upper: u[0], half_upper: u[1], force_lower: u[2], half_lower: u[3], ..*self }
    }

    /// θ_u, θ_l: the spans' angles at their contact points, rad.
    pub fn angles(&self) -> (f64, f64) {
        let w = self.weight;
        ((w * self.half_upper / self.force_upper).atan(), (w * self.half_lower / self.force_lower).atan())
    }

    /// y of the upper and lower vertex (x = 0), m.
    pub fn mid_heights(&self) -> (f64, f64) {
        let (tu, tl) = self.angles();
        let (_, yu) = shape(self.force_upper, self.weight, self.axial_stiffness, self.half_upper);
        let (_, yl) = shape(self.force_lower, self.weight, self.axial_stiffness, self.half_lower);
        (self.radius * tu.cos() - yu, -self.radius * tl.cos() - yl)
    }

    /// E = T + T²/(2EA) − w y at the upper and the lower vertex, N.
    fn invariants(&self) -> (f64, f64) {
        let (yu, yl) = self.mid_heights();
        let e = |t: f64, y: f64| t + t * t / (2.0 * self.axial_stiffness) - self.weight * y;
        (e(self.force_upper, yu), e(self.force_lower, yl))
    }

    /// Unstretched length of one pulley's arc, m (module docs, equation 4).
    fn arc_length(&self) -> f64 {
        let (tu, tl) = self.angles();
        let (e, _) = self.invariants();
        let (ea, r, w) = (self.axial_stiffness, self.radius, self.weight);
        let (a, b) = (-0.5 * PI + tl, 0.5 * PI + tu);
        let panels = 64;
        let hp = (b - a) / panels as f64;
        let rule = numerics::quadrature::Rule::Gauss(5);
        let mut sum = 0.0;
        for k in 0..panels {
            let mid = a + (k as f64 + 0.5) * hp;
            for &(xi, wt) in rule.points() {
                let phi = mid + 0.5 * hp * xi;
                let t = ea * ((1.0 + 2.0 * (e + w * r * phi.sin()) / ea).sqrt() - 1.0);
                sum += 0.5 * hp * wt * r / (1.0 + t / ea);
            }
        }
        sum
    }

    /// The four residuals of the module docs: m, m, N, m.
    fn residual(&self, length: f64) -> [f64; 4] {
        let (tu, tl) = self.angles();
        let (ea, r, w, half) = (self.axial_stiffness, self.radius, self.weight, 0.5 * self.centre_distance);
        let (xu, _) = shape(self.force_upper, w, ea, self.half_upper);
        let (xl, _) = shape(self.force_lower, w, ea, self.half_lower);
        let (eu, el) = self.invariants();
        [
            xu - (half - r * tu.sin()),
            xl - (half + r * tl.sin()),
            eu - el,
            2.0 * self.half_upper + 2.0 * self.half_lower + 2.0 * self.arc_length() - length,
        ]
    }

    /// The summary quantities of DESIGN.md's result format that the closed form gives:
    /// mid-span heights and axial forces, and each pulley's contact arc, first and last
    /// contact angle (polar, in the direction of σ). Everything else stays absent.
    pub fn summary(&self) -> Summary {
        let (tu, tl) = self.angles();
        let (yu, yl) = self.mid_heights();
        let half_pi = 0.5 * PI;
        let mut s = Summary::default();
        let globals = [(Global::YUpperMid, yu), (Global::YLowerMid, yl), (Global::TensionUpperMid, self.force_upper), (Global::TensionLowerMid, self.force_lower)];
        for (g, v) in globals {
            s.set_value(Quantity::Global(g), Some(v));
        }
        let arc = PI + tu - tl;
        // σ runs clockwise: the driven arc from its upper to its lower contact, the driver
        // arc from its lower to its upper contact (mirror images about x = 0)
        let pulleys = [(PulleyId::Driven, half_pi + tu, -half_pi + tl), (PulleyId::Driver, -half_pi - tl, half_pi - tu)];
        for (p, start, end) in pulleys {
            s.set_value(Quantity::Pulley(p, PulleyQuantity::ContactArc), Some(arc));
            s.set_value(Quantity::Pulley(p, PulleyQuantity::ContactStart), Some(start));
            s.set_value(Quantity::Pulley(p, PulleyQuantity::ContactEnd), Some(end));
        }
        s
    }
}

/// Gaussian elimination with partial pivoting of a 4 × 4 system; `None` if singular.
fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> Option<[f64; 4]> {
    for c in 0..4 {
        let p = (c..4).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[p][c] == 0.0 || !a[p][c].is_finite() {
            return None;
        }
        a.swap(c, p);
        b.swap(c, p);
        let pivot = a[c];
        for i in c + 1..4 {
            let f = a[i][c] / pivot[c];
            for (aik, pk) in a[i].iter_mut().zip(&pivot).skip(c) {
                *aik -= f * pk;
            }
            b[i] -= f * b[c];
        }
    }
    let mut x = [0.0; 4];
    for i in (0..4).rev() {
        let s: f64 = (i + 1..4).map(|k| a[i][k] * x[k]).sum();
        x[i] = (b[i] - s) / a[i][i];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The solved loop satisfies its own equations and the balance the equations do not
    /// impose: the vertical force of each span at its contact equals w s (catenary), and
    /// both pulleys carry the mirror-image arc.
    #[test]
    fn catalogue_loop_solves_and_is_consistent() {
        let lp = CatenaryLoop::solve(0.08, 0.45, 1.41, 2.0e4, 0.12 * 9.81).unwrap();
        let res = lp.residual(1.41);
        assert!(res.iter().all(|r| r.abs() < 1e-12), "{res:?}");
        assert!(lp.iterations < 30, "{} Newton iterations", lp.iterations);
        let (yu, yl) = lp.mid_heights();
        assert!(yu < 0.08 && yl < -0.08, "both spans sag below the contour: {yu}, {yl}");
        let s = lp.summary();
        assert_eq!(s.scalars().len(), 10);
        let arc = s.value(Quantity::Pulley(PulleyId::Driver, PulleyQuantity::ContactArc)).unwrap();
        let (a, b) = (
            s.value(Quantity::Pulley(PulleyId::Driver, PulleyQuantity::ContactStart)).unwrap(),
            s.value(Quantity::Pulley(PulleyId::Driver, PulleyQuantity::ContactEnd)).unwrap(),
        );
        // clockwise from the first to the last contact: the polar angle decreases by the arc
        assert!(((a - b).rem_euclid(2.0 * PI) - arc).abs() < 1e-14, "driver arc {arc} vs its ends {a} → {b}");
    }

    #[test]
    fn other_models_are_refused() {
        let mut scene = Scene::from_json_str(include_str!("../../scenes/rod-hanging.json")).unwrap();
        assert!(matches!(CatenaryLoop::of_scene(&scene), Err(ClosedFormError::NotThisModel { .. })));
        scene.belt.theory = Theory::String;
        scene.belt.bending_stiffness = None;
        scene.effects.gravity = None;
        assert!(matches!(CatenaryLoop::of_scene(&scene), Err(ClosedFormError::NotThisModel { .. })));
    }
}
