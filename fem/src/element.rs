//! Elements described by their field layout and dimension (issue 11, "One MEL element
//! core"): which fields an element carries, over how many parametric dimensions, and
//! where each nodal unknown sits in the element's local vector — instead of a fixed
//! count of 8 and hand-written index arrays.
//!
//! - 1-D Hermite elements over σ (two nodes, per node and field the value and ∂σ):
//!   [`STRING`] {s, ν} (string and Kirchhoff rod, 8 unknowns — the layout of
//!   [`crate::kinematics`]), [`COSSERAT`] {s, ν, θ} (12; spec §1.10);
//! - 2-D Bogner–Fox–Schmit bicubics over (σ, ζ) (four nodes, per node and field f, ∂σf,
//!   ∂ζf, ∂σζf): [`SHELL`] {S, ν, z} (48; spec §4.4–§4.8), with the element interface
//!   [`SurfaceElement`] and the flat-rectangle element [`BfsRectangle`].
//!
//! Local order: node-major, then field, then derivative —
//! `index(node, field, derivative) = (node · fields + field) · derivatives + derivative`.

use crate::hermite;

/// An unknown field of a belt element.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Field {
    /// Material coordinate s(σ) (1-D) or S(σ, ζ) (shell), m.
    S,
    /// Normal deflection ν, m.
    Nu,
    /// Cross-section rotation θ of the Cosserat rod, rad.
    Theta,
    /// Lateral (ζ-direction) displacement z of the shell, m.
    Z,
}

/// Parametric dimension of an element.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    /// A line element over σ (2 nodes, derivatives: value, ∂σ).
    One,
    /// A rectangle over (σ, ζ) (4 nodes, derivatives: f, ∂σ, ∂ζ, ∂σζ).
    Two,
}

/// The field layout of an element: its dimension and its fields, in local order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ElementLayout {
    /// Parametric dimension.
    pub dimension: Dimension,
    /// Fields, in local order.
    pub fields: &'static [Field],
}

/// String and Kirchhoff rod: {s, ν} on cubic Hermite lines, 8 unknowns.
pub const STRING: ElementLayout = ElementLayout { dimension: Dimension::One, fields: &[Field::S, Field::Nu] };
/// Cosserat rod: {s, ν, θ} on cubic Hermite lines, 12 unknowns.
pub const COSSERAT: ElementLayout = ElementLayout { dimension: Dimension::One, fields: &[Field::S, Field::Nu, Field::Theta] };
/// Kirchhoff–Love shell: {S, ν, z} on Bogner–Fox–Schmit rectangles, 48 unknowns.
pub const SHELL: ElementLayout = ElementLayout { dimension: Dimension::Two, fields: &[Field::S, Field::Nu, Field::Z] };

impl ElementLayout {
    /// Nodes per element.
    pub const fn nodes(&self) -> usize {
        match self.dimension {
            Dimension::One => 2,
            Dimension::Two => 4,
        }
    }

    /// Nodal unknowns per node and field (value and derivatives).
    pub const fn derivatives(&self) -> usize {
        match self.dimension {
            Dimension::One => 2,
            Dimension::Two => 4,
        }
    }

    /// Unknowns per field (all nodes).
    pub const fn per_field(&self) -> usize {
        self.nodes() * self.derivatives()
    }

    /// Unknowns of the element.
    pub const fn dofs(&self) -> usize {
        self.nodes() * self.fields.len() * self.derivatives()
    }

    /// Local index of derivative `derivative` of field number `field` at `node`.
    pub const fn index(&self, node: usize, field: usize, derivative: usize) -> usize {
        (node * self.fields.len() + field) * self.derivatives() + derivative
    }

    /// Position of `field` in the layout, if the element carries it.
    pub fn position(&self, field: Field) -> Option<usize> {
        self.fields.iter().position(|&f| f == field)
    }

    /// The local indices of one field's unknowns in per-field order (node-major, then
    /// derivative) — the order of the shape weights ([`hermite::weights`] in 1-D:
    /// (u_a, u′_a, u_b, u′_b); [`SurfaceShape`] in 2-D).
    pub fn field_indices(&self, field: usize) -> Vec<usize> {
        (0..self.nodes()).flat_map(|n| (0..self.derivatives()).map(move |d| self.index(n, field, d))).collect()
    }

    /// 1-D only: the four indices (u_a, u′_a, u_b, u′_b) of field number `field`.
    pub const fn hermite_indices(&self, field: usize) -> [usize; 4] {
        [self.index(0, field, 0), self.index(0, field, 1), self.index(1, field, 0), self.index(1, field, 1)]
    }
}

/// Per-field shape weights of a surface element at one point: f = Σ value_k q_k,
/// ∂σf = Σ d_sigma_k q_k, ∂ζf = Σ d_zeta_k q_k over one field's unknowns
/// ([`ElementLayout::field_indices`] order).
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceShape {
    /// Value weights.
    pub value: Vec<f64>,
    /// ∂σ weights.
    pub d_sigma: Vec<f64>,
    /// ∂ζ weights.
    pub d_zeta: Vec<f64>,
}

/// A 2-D element over (σ, ζ): what the shell's terms and assembly need from it.
pub trait SurfaceElement {
    /// Field layout (fields, unknown count, index map).
    fn layout(&self) -> ElementLayout;
    /// Shape weights at the reference point (ξ, η) ∈ [−1, 1]².
    fn shape(&self, xi: f64, eta: f64) -> SurfaceShape;
    /// Physical point (σ, ζ) of (ξ, η).
    fn point(&self, xi: f64, eta: f64) -> [f64; 2];
    /// Field `field` at (ξ, η) from the element's unknowns `q` (layout order): value,
    /// ∂σ, ∂ζ; `None` if the element does not carry the field.
    fn field(&self, q: &[f64], field: Field, xi: f64, eta: f64) -> Option<[f64; 3]> {
        let layout = self.layout();
        let f = layout.position(field)?;
        let shape = self.shape(xi, eta);
        let mut out = [0.0; 3];
        for (k, i) in layout.field_indices(f).into_iter().enumerate() {
            out[0] += shape.value[k] * q[i];
            out[1] += shape.d_sigma[k] * q[i];
            out[2] += shape.d_zeta[k] * q[i];
        }
        Some(out)
    }
}

/// The Bogner–Fox–Schmit bicubic on a flat rectangle [σ₀, σ₀ + h_σ] × [ζ₀, ζ₀ + h_ζ]
/// (spec §4.4): tensor products of the cubic Hermite functions of [`hermite`]. Nodes
/// 0 (σ₀, ζ₀), 1 (σ₀ + h_σ, ζ₀), 2 (σ₀, ζ₀ + h_ζ), 3 (σ₀ + h_σ, ζ₀ + h_ζ); per node and
/// field the unknowns f, ∂σf, ∂ζf, ∂σζf. Reproduces every bicubic exactly and is C¹
/// across element edges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BfsRectangle {
    /// Corner (σ₀, ζ₀), m.
    pub origin: [f64; 2],
    /// Edge lengths (h_σ, h_ζ), m.
    pub size: [f64; 2],
}

impl SurfaceElement for BfsRectangle {
    fn layout(&self) -> ElementLayout {
        SHELL
    }

    fn point(&self, xi: f64, eta: f64) -> [f64; 2] {
        [self.origin[0] + 0.5 * (1.0 + xi) * self.size[0], self.origin[1] + 0.5 * (1.0 + eta) * self.size[1]]
    }

    fn shape(&self, xi: f64, eta: f64) -> SurfaceShape {
        let [value, d_sigma, d_zeta, ..] = self.derivative_weights(xi, eta);
        SurfaceShape { value: value.to_vec(), d_sigma: d_sigma.to_vec(), d_zeta: d_zeta.to_vec() }
    }
}

/// The derivatives of a surface field that [`BfsRectangle::derivative_weights`] weighs,
/// in its row order: f, ∂σf, ∂ζf, ∂²σf, ∂σ∂ζf, ∂²ζf (a plate's curvatures need the last
/// three).
pub const SURFACE_DERIVATIVES: [(usize, usize); 6] = [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)];

impl BfsRectangle {
    /// Per-field weights at (ξ, η) of the six derivatives of [`SURFACE_DERIVATIVES`]
    /// (σ order, ζ order) over one field's 16 unknowns ([`ElementLayout::field_indices`]
    /// order: node-major, then f, ∂σf, ∂ζf, ∂σζf): ∂σ^a∂ζ^b f = Σ_k w\[row\]\[k\] q_k.
    pub fn derivative_weights(&self, xi: f64, eta: f64) -> [[f64; 16]; 6] {
        // 1-D weights in (u_a, u′_a, u_b, u′_b) order: entry 2·end + derivative; per
        // direction the value, first and second derivative rows
        let along = |t: f64, h: f64| {
            let (v, d) = hermite::weights(t, h);
            [v, d, hermite::second_weights(t, h)]
        };
        let (s, z) = (along(xi, self.size[0]), along(eta, self.size[1]));
        let mut w = [[0.0; 16]; 6];
        for node in 0..4 {
            let (a, b) = (node % 2, node / 2);
            for derivative in 0..4 {
                let (ds, dz) = (derivative % 2, derivative / 2);
                let (i, j) = (2 * a + ds, 2 * b + dz);
                for (row, &(p, q)) in SURFACE_DERIVATIVES.iter().enumerate() {
                    w[row][4 * node + derivative] = s[p][i] * z[q][j];
                }
            }
        }
        w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator in [−1, 1] (tests only need spread, not quality).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        }
    }

    #[test]
    fn layouts_count_and_number_their_unknowns_one_to_one() {
        assert_eq!((STRING.dofs(), COSSERAT.dofs(), SHELL.dofs()), (8, 12, 48));
        assert_eq!(STRING.dofs(), crate::kinematics::NDOF);
        for layout in [STRING, COSSERAT, SHELL] {
            let mut seen = vec![false; layout.dofs()];
            for f in 0..layout.fields.len() {
                for i in layout.field_indices(f) {
                    assert!(!seen[i], "index {i} used twice");
                    seen[i] = true;
                }
            }
            assert!(seen.iter().all(|&s| s), "every unknown has a place");
        }
        // the string's order is the one of kinematics: per node (s, ∂σs, ν, ∂σν)
        assert_eq!(STRING.hermite_indices(0), [0, 1, 4, 5]);
        assert_eq!(STRING.hermite_indices(1), [2, 3, 6, 7]);
        assert_eq!(SHELL.position(Field::Z), Some(2));
        assert_eq!(STRING.position(Field::Theta), None);
    }

    /// p(σ, ζ) = Σ c_mn σ^m ζ^n, m, n ≤ 3, and its derivatives ∂σ^i ∂ζ^j.
    fn bicubic(c: &[[f64; 4]; 4], s: f64, z: f64, i: usize, j: usize) -> f64 {
        let term = |x: f64, m: usize, d: usize| -> f64 {
            if m < d {
                return 0.0;
            }
            let fall: f64 = (0..d).map(|k| (m - k) as f64).product();
            fall * x.powi((m - d) as i32)
        };
        (0..4).flat_map(|m| (0..4).map(move |n| (m, n))).map(|(m, n)| c[m][n] * term(s, m, i) * term(z, n, j)).sum()
    }

    /// The element's unknowns of field `field` from a function with derivatives `f`
    /// (∂σ^i ∂ζ^j at a point), other fields 0.
    fn nodal(el: &BfsRectangle, field: usize, f: &dyn Fn(f64, f64, usize, usize) -> f64) -> Vec<f64> {
        let mut q = vec![0.0; SHELL.dofs()];
        for node in 0..4 {
            let [s, z] = el.point(if node % 2 == 0 { -1.0 } else { 1.0 }, if node / 2 == 0 { -1.0 } else { 1.0 });
            for d in 0..4 {
                q[SHELL.index(node, field, d)] = f(s, z, d % 2, d / 2);
            }
        }
        q
    }

    #[test]
    fn bfs_reproduces_bicubics_exactly() {
        let mut rng = Lcg(11);
        let el = BfsRectangle { origin: [0.3, -0.02], size: [0.07, 0.03] };
        for field in [Field::S, Field::Nu, Field::Z] {
            let mut c = [[0.0; 4]; 4];
            c.iter_mut().flatten().for_each(|v| *v = rng.next());
            let f = |s: f64, z: f64, i: usize, j: usize| bicubic(&c, s, z, i, j);
            let q = nodal(&el, SHELL.position(field).unwrap(), &f);
            for _ in 0..20 {
                let (xi, eta) = (rng.next(), rng.next());
                let [s, z] = el.point(xi, eta);
                let got = el.field(&q, field, xi, eta).unwrap();
                let want = [f(s, z, 0, 0), f(s, z, 1, 0), f(s, z, 0, 1)];
                // round-off of a sum of 16 products of O(1) terms, the derivatives ×2/h
                for (g, w) in got.iter().zip(want) {
                    assert!((g - w).abs() <= 1e-12 * (1.0 + w.abs()) * 100.0, "{field:?}: {g} vs {w}");
                }
            }
            // second derivatives from the weights, against the bicubic's (×4/h² at most)
            let f_index = SHELL.field_indices(SHELL.position(field).unwrap());
            for _ in 0..5 {
                let (xi, eta) = (rng.next(), rng.next());
                let [s, z] = el.point(xi, eta);
                let w = el.derivative_weights(xi, eta);
                for (row, &(i, j)) in SURFACE_DERIVATIVES.iter().enumerate() {
                    let got: f64 = f_index.iter().enumerate().map(|(k, &g)| w[row][k] * q[g]).sum();
                    let want = f(s, z, i, j);
                    assert!((got - want).abs() <= 1e-9 * (1.0 + want.abs()), "{field:?} ∂σ^{i}∂ζ^{j}: {got} vs {want}");
                }
            }
            // the other fields see nothing of this one
            for other in [Field::S, Field::Nu, Field::Z].into_iter().filter(|&o| o != field) {
                assert_eq!(el.field(&q, other, 0.3, -0.4).unwrap(), [0.0; 3]);
            }
        }
        assert!(el.field(&vec![0.0; 48], Field::Theta, 0.0, 0.0).is_none());
    }

    #[test]
    fn bfs_is_c1_across_a_shared_edge_for_random_nodal_data() {
        let mut rng = Lcg(7);
        // two elements of different widths meeting at σ = 0.5; shared nodes share data
        let left = BfsRectangle { origin: [0.4, 0.0], size: [0.1, 0.05] };
        let right = BfsRectangle { origin: [0.5, 0.0], size: [0.037, 0.05] };
        let mut ql = vec![0.0; 48];
        let mut qr = vec![0.0; 48];
        ql.iter_mut().chain(qr.iter_mut()).for_each(|v| *v = rng.next());
        // left's nodes 1, 3 (σ = 0.5) are right's nodes 0, 2
        for (l, r) in [(1, 0), (3, 2)] {
            for f in 0..3 {
                for d in 0..4 {
                    qr[SHELL.index(r, f, d)] = ql[SHELL.index(l, f, d)];
                }
            }
        }
        for _ in 0..10 {
            let eta = rng.next();
            for field in [Field::S, Field::Nu, Field::Z] {
                let a = left.field(&ql, field, 1.0, eta).unwrap();
                let b = right.field(&qr, field, -1.0, eta).unwrap();
                assert_eq!(left.point(1.0, eta), right.point(-1.0, eta));
                for k in 0..3 {
                    assert!((a[k] - b[k]).abs() <= 1e-12 * (1.0 + a[k].abs()) * 100.0, "{field:?} component {k}: {} vs {}", a[k], b[k]);
                }
            }
        }
        // and not across an edge whose shared data differ: the check can fail
        qr[SHELL.index(0, 1, 1)] += 1.0;
        let a = left.field(&ql, Field::Nu, 1.0, 0.0).unwrap();
        let b = right.field(&qr, Field::Nu, -1.0, 0.0).unwrap();
        assert!((a[1] - b[1]).abs() > 0.1);
    }
}
