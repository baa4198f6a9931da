//! Collocation schemes (Gauss–Legendre) and their Runge–Kutta tableaux.
//!
//! An s-stage collocation method on an interval [x_i, x_i + h] finds the polynomial
//! u of degree s with u(x_i) = y_i and u'(x_i + c_j h) = f(x_i + c_j h, u(x_i + c_j h)),
//! j = 1..s. Written with the stage values Y_j = u(x_i + c_j h) it is the implicit
//! Runge–Kutta method
//!
//! ```text
//!     Y_j     = y_i + h Σ_l a_jl f(x_i + c_l h, Y_l),     a_jl = ∫_0^{c_j} ℓ_l(t) dt,
//!     y_{i+1} = y_i + h Σ_l b_l  f(x_i + c_l h, Y_l),     b_l  = ∫_0^1   ℓ_l(t) dt,
//! ```
//!
//! with ℓ_l the Lagrange basis on the nodes c (Hairer, Nørsett & Wanner, "Solving
//! ODEs I", §II.7, Theorem 7.7). The collocation polynomial itself is
//! u(x_i + t h) = y_i + h Σ_l K_l ∫_0^t ℓ_l, K_l = f(x_i + c_l h, Y_l).
//!
//! With Gauss–Legendre nodes the node values are superconvergent of order 2s; the
//! polynomial u is accurate to O(h^{s+1}) between nodes and the collocation residual
//! u' − f(x, u) is O(h^s) (de Boor & Swartz, SIAM J. Numer. Anal. 10, 1973): that is
//! the *residual order* used by mesh adaptation.

use std::fmt;
use std::str::FromStr;

/// A collocation scheme. Serialised (and parsed) as its kebab-case name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Scheme {
    /// Gauss–Legendre, 2 stages: nodal order 4, residual order 2.
    Gauss4,
    /// Gauss–Legendre, 3 stages: nodal order 6, residual order 3.
    Gauss6,
    /// Gauss–Legendre, 4 stages: nodal order 8, residual order 4. The default: the
    /// cheapest scheme at every accuracy measured (`docs/bvp-engine.md`, "Speed").
    #[default]
    Gauss8,
}

impl Scheme {
    /// All schemes, lowest order first.
    pub const ALL: [Scheme; 3] = [Scheme::Gauss4, Scheme::Gauss6, Scheme::Gauss8];

    /// Number of collocation points s.
    pub fn stages(self) -> usize {
        match self {
            Scheme::Gauss4 => 2,
            Scheme::Gauss6 => 3,
            Scheme::Gauss8 => 4,
        }
    }

    /// Order of the node values: the global error at mesh nodes is O(h^order) = O(h^{2s}).
    pub fn order(self) -> usize {
        2 * self.stages()
    }

    /// Order q of the collocation residual u' − f(x, u) = O(h^q), q = s.
    pub fn residual_order(self) -> usize {
        self.stages()
    }

    /// Name used by serde, [`FromStr`] and the CLI: "gauss4", "gauss6", "gauss8".
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Gauss4 => "gauss4",
            Scheme::Gauss6 => "gauss6",
            Scheme::Gauss8 => "gauss8",
        }
    }

    /// Collocation nodes c_1 < … < c_s in (0, 1): the Gauss–Legendre points ξ of
    /// [`numerics::Rule::Gauss`] mapped by c = (1 + ξ)/2.
    pub fn nodes(self) -> Vec<f64> {
        let points = u8::try_from(self.stages()).expect("2 to 4 stages");
        numerics::Rule::Gauss(points).points().iter().map(|&(xi, _)| 0.5 * (1.0 + xi)).collect()
    }
}

impl fmt::Display for Scheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Scheme {
    type Err = String;
    /// Parse "gauss4" / "gauss6" / "gauss8" (case-insensitive).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let lower = s.trim().to_ascii_lowercase();
        Scheme::ALL.into_iter().find(|sc| sc.name() == lower).ok_or_else(|| {
            format!("unknown collocation scheme '{s}' (expected one of {})", Scheme::ALL.map(|sc| sc.name()).join(", "))
        })
    }
}

/// The Runge–Kutta tableau and dense-output basis of a scheme.
#[derive(Debug, Clone)]
pub(crate) struct Tableau {
    /// Stages s.
    pub s: usize,
    /// Nodes c (length s).
    pub c: Vec<f64>,
    /// a_jl, row-major s × s.
    pub a: Vec<f64>,
    /// Weights b (length s).
    pub b: Vec<f64>,
    /// Power-basis coefficients of the Lagrange polynomials: `lagrange[l][m]` is the
    /// coefficient of t^m in ℓ_l(t) (degree s − 1).
    pub lagrange: Vec<Vec<f64>>,
}

/// Σ_m p[m] t^m.
pub(crate) fn horner(p: &[f64], t: f64) -> f64 {
    p.iter().rev().fold(0.0, |acc, &c| acc * t + c)
}

/// ∫_0^t Σ_m p[m] τ^m dτ.
fn integral(p: &[f64], t: f64) -> f64 {
    p.iter().enumerate().rev().fold(0.0, |acc, (m, &c)| acc * t + c / (m + 1) as f64) * t
}

impl Tableau {
    pub fn new(scheme: Scheme) -> Self {
        let c = scheme.nodes();
        let s = c.len();
        let lagrange: Vec<Vec<f64>> = (0..s)
            .map(|l| {
                let mut p = vec![1.0];
                for (m, &cm) in c.iter().enumerate() {
                    if m == l {
                        continue;
                    }
                    let d = c[l] - cm;
                    // p ← p · (t − c_m) / d
                    let mut q = vec![0.0; p.len() + 1];
                    for (k, &pk) in p.iter().enumerate() {
                        q[k + 1] += pk / d;
                        q[k] -= cm * pk / d;
                    }
                    p = q;
                }
                p
            })
            .collect();
        let mut a = vec![0.0; s * s];
        for j in 0..s {
            for l in 0..s {
                a[j * s + l] = integral(&lagrange[l], c[j]);
            }
        }
        let b = (0..s).map(|l| integral(&lagrange[l], 1.0)).collect();
        Self { s, c, a, b, lagrange }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tableaux_match_textbook_values() {
        // Gauss 2-stage (Hairer–Wanner II, Table 7.4): a = [[1/4, 1/4 − √3/6], [1/4 + √3/6, 1/4]].
        let t = Tableau::new(Scheme::Gauss4);
        let r = 3f64.sqrt() / 6.0;
        let expected = [0.25, 0.25 - r, 0.25 + r, 0.25];
        for (x, e) in t.a.iter().zip(expected) {
            assert!((x - e).abs() < 1e-15, "{x} vs {e}");
        }
        // Gauss 3-stage: b = (5/18, 4/9, 5/18).
        let t = Tableau::new(Scheme::Gauss6);
        for (x, e) in t.b.iter().zip([5.0 / 18.0, 4.0 / 9.0, 5.0 / 18.0]) {
            assert!((x - e).abs() < 1e-15);
        }
        // Row sums of a equal c (consistency) for every scheme; Σ b = 1.
        for sc in Scheme::ALL {
            let t = Tableau::new(sc);
            for j in 0..t.s {
                let row: f64 = t.a[j * t.s..(j + 1) * t.s].iter().sum();
                assert!((row - t.c[j]).abs() < 1e-14);
            }
            assert!((t.b.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            assert!((horner(&t.lagrange[0], t.c[0]) - 1.0).abs() < 1e-13);
        }
    }

    #[test]
    fn names_round_trip() {
        for sc in Scheme::ALL {
            assert_eq!(sc.name().parse::<Scheme>().unwrap(), sc);
            assert_eq!(sc.order(), 2 * sc.stages());
        }
        assert!("gauss5".parse::<Scheme>().is_err());
    }
}
