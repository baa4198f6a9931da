//! Integration rules on the reference element ξ ∈ [−1, 1] (§7.3 of the reference).
//!
//! A rule is a value that each energy term receives (docs/fem-string.md §6): Gauss
//! n-point (n = 1…5, exact for polynomials of degree 2n − 1), Simpson (ξ = −1, 0, 1,
//! exact to degree 3) and trapezoidal (ξ = ±1, exact to degree 1; for a contact term it
//! samples the gap at the nodes only, Fig. 8b).

use std::fmt;

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

    /// `Err` with a reason if the rule has no points.
    pub fn validate(&self) -> Result<(), String> {
        if self.points().is_empty() {
            Err(format!("{self}: Gauss rules exist for 1 to 5 points"))
        } else {
            Ok(())
        }
    }
}

impl fmt::Display for Rule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each rule integrates ξ^k exactly for k ≤ its degree (∫ξ^k = 2/(k+1) for even k,
    /// 0 for odd), and not for degree + 1 (even degree + 1 for the symmetric rules).
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
        assert!(Rule::Gauss(6).validate().is_err());
        assert!(Rule::Gauss(0).validate().is_err());
    }
}
