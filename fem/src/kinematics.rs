//! MEL kinematics of one element on the compound contour (§5 of the reference;
//! docs/fem-string.md §2, §5).
//!
//! An element's 8 local unknowns are q = (s_a, ∂σs_a, ν_a, ∂σν_a, s_b, ∂σs_b, ν_b,
//! ∂σν_b) (units m, 1, m, 1). Everything here is generic over the number type `D` so that
//! the same code gives values (f64) and exact derivatives (dual numbers).

use drive::contour::{Contour, Region};

use crate::element::{ElementLayout, STRING};
use crate::hermite;
use crate::mesh::ElementGeometry;

/// The number types element energies are evaluated with: f64 and num-dual's duals
/// (one definition for `bvp` and `fem`).
pub use numerics::Scalar;

/// Number of local unknowns of a string element ([`crate::element::STRING`]).
pub const NDOF: usize = STRING.dofs();

/// Local indices (u_a, u′_a, u_b, u′_b) of s in the string layout.
pub const S_DOFS: [usize; 4] = STRING.hermite_indices(0);
/// Local indices (u_a, u′_a, u_b, u′_b) of ν in the string layout.
pub const NU_DOFS: [usize; 4] = STRING.hermite_indices(1);

/// Physical parameters of the energy terms of a scene; a term whose parameter is
/// `None` is not assembled (docs/fem-string.md §4).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TermParams {
    /// EA, N (> 0). The strain energy is always present.
    pub axial_stiffness: f64,
    /// ρ g, N per unstretched metre, if the gravity term is assembled.
    pub weight: Option<f64>,
    /// Penalty factor P, N/m², if the contact term is assembled.
    pub penalty: Option<f64>,
    /// EI, N·m², if the bending energy is assembled (Kirchhoff rod, docs/fem-rod.md K7).
    pub bending_stiffness: Option<f64>,
}

/// Everything an element's energy depends on apart from its unknowns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementContext {
    /// σ-range and region.
    pub geometry: ElementGeometry,
    /// The contour (g, t_g, n_g of eq. 38).
    pub contour: Contour,
    /// The active terms and their parameters.
    pub params: TermParams,
    /// Augmented approximation (docs/fem-rod.md §3, K9) at the start / end node: the
    /// element is polar, the node is a transition and its slope pair is the Cartesian
    /// side's primary pair, so the element's slopes there are (1 + ν/R) times the
    /// gathered ones. Always false for the string (separate slopes).
    pub augmented: [bool; 2],
}

/// S, ∂σS, ν, ∂σν at one point of an element.
#[derive(Debug, Clone, Copy)]
pub struct PointFields<D> {
    /// σ of the point, m.
    pub sigma: f64,
    /// Material coordinate S, m.
    pub s: D,
    /// ∂σS (> 0 for an admissible state).
    pub ds: D,
    /// Deflection ν, m.
    pub nu: D,
    /// ∂σν.
    pub dnu: D,
    /// ∂²σν (bending, docs/fem-rod.md K2).
    pub d2nu: D,
}

impl ElementContext {
    /// α of eq. (38) on this element: 0 on a span, 1/R on an arc (from the element's
    /// region, also at its end point where the contour already belongs to the next region).
    pub fn alpha(&self) -> f64 {
        if self.geometry.region.is_polar() {
            1.0 / self.contour.radius()
        } else {
            0.0
        }
    }

    /// σ at local coordinate ξ.
    pub fn sigma(&self, xi: f64) -> f64 {
        self.geometry.sigma_a + 0.5 * (1.0 + xi) * self.geometry.h
    }

    /// Jacobian dσ/dξ = h/2.
    pub fn jacobian(&self) -> f64 {
        0.5 * self.geometry.h
    }

    /// The fields at ξ from the local unknowns (eq. 43).
    #[inline]
    pub fn fields<D: Scalar>(&self, q: &[D; NDOF], xi: f64) -> PointFields<D> {
        self.layout_fields(STRING, q, xi)
    }

    /// The fields S, ∂σS, ν, ∂σν, ∂²σν at ξ of an element of any 1-D Hermite `layout`
    /// from its N local unknowns (layout order): every 1-D layout carries s as field 0
    /// and ν as field 1 ([`crate::element`]); further fields (θ) are read by
    /// [`Self::field`].
    #[inline]
    pub fn layout_fields<D: Scalar, const N: usize>(&self, layout: ElementLayout, q: &[D; N], xi: f64) -> PointFields<D> {
        let (wv, wd) = hermite::weights(xi, self.geometry.h);
        let comb = |w: &[f64; 4], i: [usize; 4]| -> D { q[i[0]] * w[0] + q[i[1]] * w[1] + q[i[2]] * w[2] + q[i[3]] * w[3] };
        let w2 = hermite::second_weights(xi, self.geometry.h);
        let (s, nu) = (layout.hermite_indices(0), layout.hermite_indices(1));
        PointFields {
            sigma: self.sigma(xi),
            s: comb(&wv, s),
            ds: comb(&wd, s),
            nu: comb(&wv, nu),
            dnu: comb(&wd, nu),
            d2nu: comb(&w2, nu),
        }
    }

    /// Value, ∂σ and ∂²σ at ξ of field number `field` of a 1-D Hermite `layout`, from
    /// the element's N local unknowns in layout order — for any field set ({s, ν},
    /// {s, ν, θ}); [`Self::fields`] is the string layout's named version.
    #[inline]
    pub fn field<D: Scalar, const N: usize>(&self, layout: ElementLayout, q: &[D; N], field: usize, xi: f64) -> [D; 3] {
        let (wv, wd) = hermite::weights(xi, self.geometry.h);
        let w2 = hermite::second_weights(xi, self.geometry.h);
        let i = layout.hermite_indices(field);
        let comb = |w: &[f64; 4]| -> D { q[i[0]] * w[0] + q[i[1]] * w[1] + q[i[2]] * w[2] + q[i[3]] * w[3] };
        [comb(&wv), comb(&wd), comb(&w2)]
    }

    /// The effective local unknowns q̃ = m(q) of the augmented approximation
    /// (docs/fem-rod.md §3, K9): at a flagged node the slopes (∂σs, ∂σν) are multiplied
    /// by f = 1 + ν/R with ν that node's deflection; elsewhere q̃ = q. Generic, so that
    /// AD through the element energy differentiates the map exactly.
    #[inline]
    pub fn effective<D: Scalar>(&self, q: &[D; NDOF]) -> [D; NDOF] {
        let mut out = *q;
        let a = self.alpha();
        // per node (ends 0, 1): ν at the node, ∂σs and ∂σν scaled
        for (flag, end) in self.augmented.iter().zip([0usize, 2]) {
            if *flag {
                let f = q[NU_DOFS[end]] * a + 1.0;
                out[S_DOFS[end + 1]] = q[S_DOFS[end + 1]] * f;
                out[NU_DOFS[end + 1]] = q[NU_DOFS[end + 1]] * f;
            }
        }
        out
    }

    /// The centreline unknowns {s, ν} of an element of any 1-D `layout` in the string
    /// order ([`crate::element::STRING`]), after the augmented map of the element's
    /// flagged nodes ([`Self::effective`], docs/fem-rod.md K9; the Cosserat element's map
    /// (C3) scales ∂σs and ∂σν the same way) — the identity for the string. The drive's
    /// contact, friction and transport-inertia terms act on these only
    /// (docs/fem-cosserat.md §7); generic so that AD differentiates through the map.
    #[inline]
    pub fn centreline<D: Scalar, const N: usize>(&self, layout: ElementLayout, q: &[D; N]) -> [D; NDOF] {
        let mut out = [q[0]; NDOF];
        for f in 0..2 {
            for (i, j) in STRING.hermite_indices(f).into_iter().zip(layout.hermite_indices(f)) {
                out[i] = q[j];
            }
        }
        if self.augmented.iter().any(|&a| a) {
            self.effective(&out)
        } else {
            out
        }
    }

    /// Rate of the tangent angle per contour length θ_σ = (r′ × r″)/|r′|²
    /// (docs/fem-rod.md K3), 1/m.
    #[inline]
    pub fn angle_rate<D: Scalar>(&self, p: &PointFields<D>) -> D {
        let al = self.alpha();
        let a = p.nu * al + 1.0;
        let b = p.dnu;
        let c = p.dnu * (2.0 * al);
        let d = p.d2nu - a * al;
        (a * d - b * c) / (a * a + b * b)
    }

    /// Kirchhoff curvature κ = θ_σ/∂σS per unstretched length (K4), 1/m.
    #[inline]
    pub fn curvature<D: Scalar>(&self, p: &PointFields<D>) -> D {
        self.angle_rate(p) / p.ds
    }

    /// ∂²σν at ξ (post-processing: curvature of the belt).
    pub fn second_derivative_nu(&self, q: &[f64; NDOF], xi: f64) -> f64 {
        let w = hermite::second_weights(xi, self.geometry.h);
        NU_DOFS.iter().zip(w).map(|(&i, wk)| q[i] * wk).sum()
    }

    /// Position r, ∂σr and ∂²σr at ξ (f64 post-processing), from (F1), (F2) and
    /// ∂²σr = 2α ∂σν t_g + (∂²σν − α(1 + αν)) n_g (eq. 38 applied twice).
    pub fn curve(&self, q: &[f64; NDOF], xi: f64) -> [[f64; 2]; 3] {
        self.curve_at(&self.fields(q, xi))
    }

    /// [`Self::curve`] from the point fields (∂²σν included), for any layout.
    pub fn curve_at(&self, p: &PointFields<f64>) -> [[f64; 2]; 3] {
        let d2 = p.d2nu;
        let a = self.alpha();
        let t = self.contour.t_g(p.sigma);
        let n = self.contour.n_g(p.sigma);
        let r = self.position(p);
        let c1 = (1.0 + a * p.nu, p.dnu);
        let c2 = (2.0 * a * p.dnu, d2 - a * (1.0 + a * p.nu));
        [
            r,
            [c1.0 * t[0] + c1.1 * n[0], c1.0 * t[1] + c1.1 * n[1]],
            [c2.0 * t[0] + c2.1 * n[0], c2.0 * t[1] + c2.1 * n[1]],
        ]
    }

    /// |∂σ r| = √((1 + αν)² + (∂σν)²), eq. (F2).
    #[inline]
    pub fn tangent_length<D: Scalar>(&self, p: &PointFields<D>) -> D {
        let a = p.nu * self.alpha() + 1.0;
        (a * a + p.dnu * p.dnu).sqrt()
    }

    /// Stretch λ = |∂σ r| / ∂σS, eq. (F4).
    #[inline]
    pub fn stretch<D: Scalar>(&self, p: &PointFields<D>) -> D {
        self.tangent_length(p) / p.ds
    }

    /// Position r = g + ν n_g (eq. 27), m.
    #[inline]
    pub fn position<D: Scalar>(&self, p: &PointFields<D>) -> [D; 2] {
        let (g, n) = self.contour.point_and_normal(p.sigma);
        [p.nu * n[0] + g[0], p.nu * n[1] + g[1]]
    }

    /// Height y = g_y + ν n_{g,y}, m.
    #[inline]
    pub fn height<D: Scalar>(&self, p: &PointFields<D>) -> D {
        let (g, n) = self.contour.point_and_normal(p.sigma);
        p.nu * n[1] + g[1]
    }

    /// Gap γ to the nearest pulley surface at the point, m (docs/fem-string.md F10):
    /// ν on an arc; √((x − x_k)² + (R + ν)²) − R on a span point with |x − x_k| < R;
    /// `None` where no pulley can be reached (the rest of a span).
    #[inline]
    pub fn gap<D: Scalar>(&self, p: &PointFields<D>) -> Option<D> {
        span_gap(&self.contour, self.geometry.region, p.sigma, p.nu)
    }
}

/// The gap of (F10) at σ in `region` for deflection ν (see [`ElementContext::gap`]).
#[inline]
pub fn span_gap<D: Scalar>(contour: &Contour, region: Region, sigma: f64, nu: D) -> Option<D> {
    if region.is_polar() {
        return Some(nu);
    }
    let r = contour.radius();
    let x = contour.g(sigma)[0];
    let half = 0.5 * contour.centre_distance();
    let dx = if (x - half).abs() < r {
        x - half
    } else if (x + half).abs() < r {
        x + half
    } else {
        return None;
    };
    let a = nu + r;
    Some((a * a + dx * dx).sqrt() - r)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On an arc the position is C + (R + ν) n_g and the gap is ν; on a span near a
    /// pulley the gap is the distance to the centre minus R.
    #[test]
    fn position_and_gap() {
        let contour = Contour::new(0.08, 0.45).unwrap();
        let r = contour.radius();
        let ctx = |region: Region, sa: f64, h: f64| ElementContext {
            geometry: ElementGeometry { sigma_a: sa, h, region },
            contour,
            params: TermParams { axial_stiffness: 1.0, weight: None, penalty: None, bending_stiffness: None },
            augmented: [false; 2],
        };
        // driven arc element, constant ν = 0.01
        let e = ctx(Region::DrivenArc, 0.45, 0.02);
        let q = [0.45, 1.0, 0.01, 0.0, 0.47, 1.0, 0.01, 0.0];
        let p = e.fields(&q, 0.3);
        let pos = e.position(&p);
        let c = contour.pulley_centre(drive::contour::Pulley::Driven);
        let dist = (pos[0] - c[0]).hypot(pos[1] - c[1]);
        assert!((dist - (r + 0.01)).abs() < 1e-15);
        assert!((e.gap(&p).unwrap() - 0.01).abs() < 1e-15);
        // stretch with ∂σS = 1: λ = 1 + αν
        assert!((e.stretch(&p) - (1.0 + 0.01 / r)).abs() < 1e-14);
        // upper span element ending at the driven top: x = 0.2 is 0.025 left of the centre
        let e = ctx(Region::UpperSpan, 0.42, 0.03);
        let q = [0.42, 1.0, -0.001, 0.0, 0.45, 1.0, -0.001, 0.0];
        let p = e.fields(&q, 2.0 * (0.425 - 0.42) / 0.03 - 1.0);
        let g = e.gap(&p).unwrap();
        let expect = (0.025f64.powi(2) + (r - 0.001).powi(2)).sqrt() - r;
        assert!((g - expect).abs() < 1e-15, "{g} vs {expect}");
        // mid upper span: no pulley within reach
        let e = ctx(Region::UpperSpan, 0.2, 0.03);
        let p = e.fields(&q, 0.0);
        assert!(e.gap(&p).is_none());
    }

    /// docs/fem-rod.md §3 (K8, K9): with one shared slope pair per transition and the
    /// augmented map on the polar side, position r, the material derivative dr/ds =
    /// ∂σr/∂σS (stretch and direction) and the unit tangent are continuous across each of
    /// the four Cartesian/polar transitions for random nodal values, to round-off
    /// (1e-13 relative: a handful of operations on O(1) numbers). Without the map (the
    /// string's separate slopes filled with independent random values) they are not —
    /// the check can fail.
    #[test]
    fn augmented_transitions_are_c1_in_physical_space() {
        use crate::dofs::{augmented_flags, DofMap};
        use crate::mesh::Mesh;
        let contour = Contour::new(0.08, 0.45).unwrap();
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut rand = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let params = TermParams { axial_stiffness: 1.0, weight: None, penalty: None, bending_stiffness: Some(1.0) };
        let close = |a: [f64; 2], b: [f64; 2], tol: f64| (a[0] - b[0]).hypot(a[1] - b[1]) <= tol;
        for (n, separate) in [(8, false), (20, false), (64, false), (20, true)] {
            let mesh = Mesh::new(contour, n, 1.0).unwrap();
            let map = DofMap::with_transition_slopes(&mesh, separate);
            let flags = augmented_flags(&mesh, separate);
            let mut broken = 0;
            for _trial in 0..25 {
                // random nodal values: s increasing-ish, ν of either sign up to R/4, slopes O(1)
                let z: Vec<f64> = (0..map.len()).map(|_| rand()).collect();
                let z: Vec<f64> = z
                    .iter()
                    .zip(map.kinds())
                    .map(|(v, k)| match k {
                        crate::dofs::DofKind::Value => 0.04 * v,
                        crate::dofs::DofKind::Slope => 1.0 + 0.8 * v,
                    })
                    .collect();
                for &k in &mesh.transition_nodes() {
                    let left = (k + n - 1) % n;
                    let ctx = |e: usize| ElementContext { geometry: mesh.elements()[e], contour, params, augmented: flags[e] };
                    let (cl, cr) = (ctx(left), ctx(k));
                    let ql = cl.effective(&map.gather(left, &z, 1.3));
                    let qr = cr.effective(&map.gather(k, &z, 1.3));
                    let [rl, dl, _] = cl.curve(&ql, 1.0);
                    let [rr, dr, _] = cr.curve(&qr, -1.0);
                    let (sl, sr) = (cl.fields(&ql, 1.0).ds, cr.fields(&qr, -1.0).ds);
                    let dsl = [dl[0] / sl, dl[1] / sl];
                    let dsr = [dr[0] / sr, dr[1] / sr];
                    let (tl, tr) = (dl[0].hypot(dl[1]), dr[0].hypot(dr[1]));
                    assert!(close(rl, rr, 1e-14), "position jumps at node {k}: {rl:?} vs {rr:?}");
                    let ok = close(dsl, dsr, 1e-13 * dsl[0].hypot(dsl[1]))
                        && close([dl[0] / tl, dl[1] / tl], [dr[0] / tr, dr[1] / tr], 1e-13);
                    if separate {
                        broken += usize::from(!ok);
                    } else {
                        assert!(ok, "n = {n}, node {k}: dr/ds {dsl:?} vs {dsr:?}");
                    }
                }
            }
            if separate {
                assert_eq!(broken, 100, "independent slopes should break C¹ at every transition");
            }
        }
    }
}
