//! Integration rules on the reference interval ξ ∈ [−1, 1]: Gauss–Legendre n-point
//! (n = 1…5, exact for polynomials of degree 2n − 1), Simpson (ξ = −1, 0, 1, exact to
//! degree 3) and trapezoidal (ξ = ±1, exact to degree 1).
//!
//! In `fem` a rule is a value each energy term receives (docs/fem-string.md §6, §7.3 of
//! the reference; the trapezoidal rule makes a contact term sample the gap at the nodes
//! only, Fig. 8b); in `bvp` the Gauss–Legendre points are the collocation nodes.

use std::fmt;

use thiserror::Error;

/// A rule that does not exist.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum QuadratureError {
    /// Gauss rules are tabulated for 1 to 5 points.
    #[error("gauss{points}: Gauss rules exist for 1 to 5 points")]
    GaussPoints { points: u8 },
}

/// An integration rule on ξ ∈ [−1, 1]: points and weights (weights sum to 2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Rule {
    /// Gauss–Legendre with n points, 1 ≤ n ≤ 5.
    Gauss(u8),
    /// Simpson: ξ = −1, 0, 1 with weights ⅓, ⁴⁄₃, ⅓.
    Simpson,
    /// Trapezoidal: ξ = ±1 with weights 1.
    Trapezoidal,
}

const G1: [(f64, f64); 1] = [(0.0, 2.0)];
const G2: [(f64, f64); 2] = [(-0.577_350_269_189_625_8, 1.0), (0.577_350_269_189_625_8, 1.0)];
const G3: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 0.555_555_555_555_555_6),
    (0.0, 0.888_888_888_888_889),
    (0.774_596_669_241_483_4, 0.555_555_555_555_555_6),
];
const G4: [(f64, f64); 4] = [
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_8),
    (-0.339_981_043_584_856_3, 0.652_145_154_862_546_2),
    (0.339_981_043_584_856_3, 0.652_145_154_862_546_2),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_8),
];
const G5: [(f64, f64); 5] = [
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.0, 0.568_888_888_888_888_9),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];
const SIMPSON: [(f64, f64); 3] = [(-1.0, 1.0 / 3.0), (0.0, 4.0 / 3.0), (1.0, 1.0 / 3.0)];
const TRAPEZOIDAL: [(f64, f64); 2] = [(-1.0, 1.0), (1.0, 1.0)];

impl Rule {
    /// (ξ, weight) pairs. A Gauss rule with n outside 1…5 has no points (it is rejected
    /// by [`Rule::validate`] before use).
    pub fn points(&self) -> &'static [(f64, f64)] {
        match self {
            Rule::Gauss(1) => &G1,
            Rule::Gauss(2) => &G2,
            Rule::Gauss(3) => &G3,
            Rule::Gauss(4) => &G4,
            Rule::Gauss(5) => &G5,
            Rule::Gauss(_) => &[],
            Rule::Simpson => &SIMPSON,
            Rule::Trapezoidal => &TRAPEZOIDAL,
        }
    }

    /// Short name used in term labels: `gauss3`, `simpson`, `trapezoidal`.
    pub fn name(&self) -> String {
        match self {
            Rule::Gauss(n) => format!("gauss{n}"),
            Rule::Simpson => "simpson".into(),
            Rule::Trapezoidal => "trapezoidal".into(),
        }
    }

    /// Highest polynomial degree integrated exactly.
    pub fn exact_degree(&self) -> u32 {
        match self {
            Rule::Gauss(n) => 2 * u32::from(*n) - 1,
            Rule::Simpson => 3,
            Rule::Trapezoidal => 1,
        }
    }

    /// The part of [−1, 1] that point `a`'s weight stands for: the weights laid end to
    /// end in point order, [−1 + Σ_{b<a} w_b, −1 + Σ_{b≤a} w_b]. The cells tile [−1, 1];
    /// each holds its point, at its middle for a symmetric rule's inner points and at an
    /// end for the end points of a closed rule (Simpson: [−1, −⅔], [−⅔, ⅔], [⅔, 1]).
    /// Integrating an integrand that is cut inside an element (a contact zone's edge) by
    /// the fraction of each cell on the kept side, times the point's value, makes the
    /// cut's position count continuously instead of by whole points
    /// (docs/fem-shell.md §7 (b)).
    ///
    /// # Panics
    /// If `a` is not a point of the rule.
    pub fn cell(&self, a: usize) -> [f64; 2] {
        let points = self.points();
        assert!(a < points.len(), "point {a} of {self}");
        let start = -1.0 + points[..a].iter().map(|p| p.1).sum::<f64>();
        // the last cell ends at 1 exactly, whatever the weights' rounding
        [start, if a + 1 == points.len() { 1.0 } else { start + points[a].1 }]
    }

    /// Check that the rule has points.
    ///
    /// # Errors
    /// [`QuadratureError::GaussPoints`] for a Gauss rule outside 1…5 points.
    pub fn validate(&self) -> Result<(), QuadratureError> {
        match *self {
            Rule::Gauss(points) if self.points().is_empty() => Err(QuadratureError::GaussPoints { points }),
            _ => Ok(()),
        }
    }
}

/// The Lagrange interpolant through the points (ξ_i, v_i) (distinct ξ_i), at ξ — inside
/// their range an interpolation, outside it an extrapolation (of degree n − 1: exact for
/// polynomials of that degree, and amplifying a non-polynomial field's error by
/// Σ|ℓ_i(ξ)|, e.g. 1.73 for two Gauss points extrapolated to ξ = ±1).
pub fn lagrange(points: &[(f64, f64)], xi: f64) -> f64 {
    let mut sum = 0.0;
    for (i, &(xi_i, v)) in points.iter().enumerate() {
        let mut w = 1.0;
        for (j, &(xi_j, _)) in points.iter().enumerate() {
            if i != j {
                w *= (xi - xi_j) / (xi_i - xi_j);
            }
        }
        sum += w * v;
    }
    sum
}

impl fmt::Display for Rule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The interpolant through a rule's points reproduces every polynomial of degree
    /// n − 1 at any ξ, the ends included (the frame's extrapolation of Gauss-point
    /// states to the nodes), to round-off; through two points it is the line
    /// (v(ξ) = 3 − 2ξ at ξ = ±1: 5 and 1), and a polynomial of degree n is not
    /// reproduced at an end (the extrapolation's error is the field's, not hidden).
    #[test]
    fn lagrange_reproduces_polynomials_below_the_point_count() {
        for n in 1..=5u8 {
            let xi: Vec<f64> = Rule::Gauss(n).points().iter().map(|p| p.0).collect();
            for degree in 0..n as i32 {
                let f = |x: f64| (0..=degree).map(|k| (k as f64 + 1.0) * x.powi(k)).sum::<f64>();
                let points: Vec<(f64, f64)> = xi.iter().map(|&x| (x, f(x))).collect();
                for at in [-1.0, -0.3, 0.0, 0.7, 1.0] {
                    assert!((lagrange(&points, at) - f(at)).abs() <= 1e-12 * f(at).abs().max(1.0), "gauss{n}, degree {degree}, ξ = {at}");
                }
            }
            let g = |x: f64| x.powi(n as i32);
            let points: Vec<(f64, f64)> = xi.iter().map(|&x| (x, g(x))).collect();
            assert!((lagrange(&points, 1.0) - 1.0).abs() > 1e-3, "gauss{n} reproduced ξ^{n}");
        }
        let line = [(-0.5, 4.0), (0.5, 2.0)];
        assert!((lagrange(&line, -1.0) - 5.0).abs() < 1e-15 && (lagrange(&line, 1.0) - 1.0).abs() < 1e-15);
    }

    /// Each rule integrates ξ^k exactly for k ≤ its degree (∫ξ^k = 2/(k+1) for even k,
    /// 0 for odd), and not for degree + 1 (every rule here has odd degree 2n − 1 or 3 or
    /// 1, so degree + 1 is even and the error is the rule's nonzero error constant: at
    /// least 1e-3, far above round-off).
    /// The cells tile [−1, 1] in order, each as long as its weight and holding its point;
    /// Simpson's are [−1, −⅔], [−⅔, ⅔], [⅔, 1].
    #[test]
    fn cells_tile_the_interval_by_the_weights() {
        for rule in [Rule::Gauss(1), Rule::Gauss(2), Rule::Gauss(3), Rule::Gauss(4), Rule::Gauss(5), Rule::Simpson, Rule::Trapezoidal] {
            let points = rule.points();
            let mut end = -1.0;
            for (a, &(x, w)) in points.iter().enumerate() {
                let [lo, hi] = rule.cell(a);
                assert!((lo - end).abs() < 1e-15 && (hi - lo - w).abs() < 1e-15, "{rule} cell {a}: [{lo}, {hi}] after {end}, weight {w}");
                assert!(lo <= x && x <= hi, "{rule} point {x} outside its cell [{lo}, {hi}]");
                end = hi;
            }
            assert_eq!(end, 1.0, "{rule}");
        }
        let third = 2.0 / 3.0;
        let simpson = [0, 1, 2].map(|a| Rule::Simpson.cell(a));
        assert!(simpson.iter().flatten().zip([-1.0, -third, -third, third, third, 1.0]).all(|(c, e)| (c - e).abs() < 1e-15), "{simpson:?}");
    }

    #[test]
    fn exactness() {
        let rules = [
            Rule::Gauss(1),
            Rule::Gauss(2),
            Rule::Gauss(3),
            Rule::Gauss(4),
            Rule::Gauss(5),
            Rule::Simpson,
            Rule::Trapezoidal,
        ];
        for rule in rules {
            rule.validate().unwrap();
            let w: f64 = rule.points().iter().map(|p| p.1).sum();
            assert!((w - 2.0).abs() < 1e-15, "{rule}: weights sum {w}");
            let deg = rule.exact_degree();
            for k in 0..=deg + 1 {
                let q: f64 = rule.points().iter().map(|&(x, w)| w * x.powi(k as i32)).sum();
                let exact = if k % 2 == 0 { 2.0 / (k as f64 + 1.0) } else { 0.0 };
                if k <= deg {
                    assert!((q - exact).abs() < 1e-14, "{rule} degree {k}: {q} vs {exact}");
                } else {
                    assert!((q - exact).abs() > 1e-3, "{rule} should not be exact at degree {k}");
                }
            }
        }
        assert_eq!(Rule::Gauss(6).validate(), Err(QuadratureError::GaussPoints { points: 6 }));
        assert!(Rule::Gauss(0).validate().is_err());
    }
}

#[cfg(test)]
mod polynomial_tests {
    use super::*;

    /// Full polynomials (all monomials up to the degree, with unequal coefficients) on a
    /// general interval [a, b] by the affine map x = (a + b)/2 + (b − a)/2 ξ: exact to
    /// round-off at the rule's degree; one degree above the leading term's error
    /// c_{d+1} ∫ ≠ 0 shows.
    #[test]
    fn polynomials_on_an_interval() {
        let (a, b) = (0.3_f64, 2.1_f64);
        for rule in [Rule::Gauss(1), Rule::Gauss(2), Rule::Gauss(3), Rule::Gauss(4), Rule::Gauss(5), Rule::Simpson, Rule::Trapezoidal] {
            let deg = rule.exact_degree() as usize;
            for d in [deg, deg + 1] {
                let coef: Vec<f64> = (0..=d).map(|k| 1.0 + 0.5 * k as f64).collect();
                let p = |x: f64| coef.iter().rev().fold(0.0, |acc, c| acc * x + c);
                let exact: f64 = coef.iter().enumerate().map(|(k, c)| c * (b.powi(k as i32 + 1) - a.powi(k as i32 + 1)) / (k as f64 + 1.0)).sum();
                let q: f64 = rule.points().iter().map(|&(xi, w)| 0.5 * (b - a) * w * p(0.5 * (a + b) + 0.5 * (b - a) * xi)).sum();
                let rel = (q - exact).abs() / exact.abs();
                if d == deg {
                    assert!(rel < 1e-14, "{rule} degree {d}: relative error {rel:e}");
                } else {
                    assert!(rel > 1e-10, "{rule} should not be exact at degree {d} (relative error {rel:e})");
                }
            }
        }
    }
}
