//! The shell's elements on the compound contour: which element columns are polar
//! (α = 1/R) and which of their σ-edges are Cartesian/polar transitions
//! ([`TransitionSides`]), the fields {S, ν, z} of an element with the augmented C¹
//! construction at those edges ([`ShellElement::fields`], docs/fem-shell.md §5), and the
//! material derivatives (37) of the position ([`material_derivatives`]).
//!
//! At a transition α jumps, so plain BFS fields that are C¹ in (σ, ζ) give a position
//! whose material derivatives (37) jump. A transition node's σ-slopes (∂σX, ∂σ∂ζX) are the
//! *Cartesian* side's; the polar element next to the transition adds, for each field X,
//!
//!   H(ξ) ν_T(η) D_C(η) / R                                                 (fem-shell.md S12)
//!
//! with H the Hermite σ-slope function of the transition end, D_C the ζ-interpolant of the
//! edge nodes' σ-slopes and ν_T that of their deflections: then
//! ∂σX_polar = (1 + ν/R) ∂σX_Cartesian along the whole edge (S11), and (37) is continuous
//! for every ζ. The correction is bilinear in the unknowns and of degree 6 in ζ.
//!
//! Element unknowns: the surface assembler's local order, field-major —
//! `16 · field + 4 · node + derivative` with fields S, ν, z ([`S`], [`NU`], [`Z`]), nodes in
//! BFS order and derivatives f, ∂σf, ∂ζf, ∂σ∂ζf ([`crate::surface::dofs`]). Point values:
//! per field the six rows of [`crate::element::SURFACE_DERIVATIVES`] (f, ∂σf, ∂ζf, ∂²σf,
//! ∂σ∂ζf, ∂²ζf).

use drive::contour::Contour;

use crate::element::{BfsRectangle, Field};
use crate::hermite;
use crate::surface::assembly::QuadraticTerm;
use crate::surface::dofs::{PointDerivative, PER_FIELD};
use crate::surface::mesh::SurfaceMesh;
use crate::Scalar;

use super::ShellError;

/// Field slot of the material coordinate S.
pub const S: usize = 0;
/// Field slot of the normal deflection ν.
pub const NU: usize = 1;
/// Field slot of the lateral position z.
pub const Z: usize = 2;
/// Unknowns of a shell element (3 fields × 16).
pub const SHELL_DOFS: usize = 3 * PER_FIELD;

/// Transitions must lie on σ-nodes to this fraction of the loop length.
pub const NODE_TOLERANCE: f64 = 1e-10;

/// Which σ-edges of a polar element column are Cartesian/polar transitions (there its
/// σ-slope terms are augmented). Both false for a Cartesian column.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Augmented {
    /// The edge at the element's start σ_i (ξ = −1).
    pub start: bool,
    /// The edge at the element's end σ_{i+1} (ξ = +1).
    pub end: bool,
}

/// One column of elements [σ_i, σ_{i+1}] × width: its α and its augmented edges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Column {
    /// α of eq. (38): 0 (span) or 1/R (arc), 1/m.
    pub alpha: f64,
    /// Transition edges (polar columns only).
    pub augmented: Augmented,
}

/// The columns of a surface mesh laid on a contour.
#[derive(Debug, Clone, PartialEq)]
pub struct TransitionSides {
    radius: f64,
    columns: Vec<Column>,
}

impl TransitionSides {
    /// The columns of `mesh` on `contour`: α from the region of the column's midpoint, an
    /// augmented edge where a polar column meets a Cartesian one.
    ///
    /// # Errors
    /// [`ShellError::LengthMismatch`] (mesh length ≠ L_geom beyond [`NODE_TOLERANCE`]),
    /// [`ShellError::TransitionNotANode`] (a transition farther than
    /// [`NODE_TOLERANCE`] · L_geom from every σ-node).
    pub fn new(contour: &Contour, mesh: &SurfaceMesh) -> Result<TransitionSides, ShellError> {
        let length = contour.length();
        let tolerance = NODE_TOLERANCE * length;
        if (mesh.length() - length).abs() > tolerance {
            return Err(ShellError::LengthMismatch { mesh: mesh.length(), contour: length });
        }
        let nodes = mesh.sigma_nodes();
        for sigma in contour.transitions() {
            let nearest = nodes.iter().copied().min_by(|a, b| (a - sigma).abs().total_cmp(&(b - sigma).abs())).unwrap_or(f64::NAN);
            if (nearest - sigma).abs().is_nan() || (nearest - sigma).abs() > tolerance {
                return Err(ShellError::TransitionNotANode { sigma, nearest });
            }
        }
        let n = mesh.sigma_elements();
        let end = |i: usize| if i + 1 == n { mesh.length() } else { nodes[i + 1] };
        let polar: Vec<bool> = (0..n).map(|i| contour.region(0.5 * (nodes[i] + end(i))).is_polar()).collect();
        let radius = contour.radius();
        let columns = (0..n)
            .map(|i| {
                let (before, after) = (polar[(i + n - 1) % n], polar[(i + 1) % n]);
                if polar[i] {
                    Column { alpha: 1.0 / radius, augmented: Augmented { start: !before, end: !after } }
                } else {
                    Column { alpha: 0.0, augmented: Augmented::default() }
                }
            })
            .collect();
        Ok(TransitionSides { radius, columns })
    }

    /// The columns of a flat periodic strip: `columns` Cartesian columns (α = 0), no
    /// transition (R = ∞, unused).
    pub fn strip(columns: usize) -> TransitionSides {
        TransitionSides { radius: f64::INFINITY, columns: vec![Column { alpha: 0.0, augmented: Augmented::default() }; columns] }
    }

    /// The same columns with the augmentation dropped (the plain BFS map at the
    /// transitions, for comparisons).
    pub fn without_augmentation(&self) -> TransitionSides {
        TransitionSides { radius: self.radius, columns: self.columns.iter().map(|c| Column { augmented: Augmented::default(), ..*c }).collect() }
    }

    /// Number of columns (σ-elements).
    pub fn columns(&self) -> usize {
        self.columns.len()
    }

    /// R of the contour, m.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Column i (σ-element i).
    pub fn column(&self, i: usize) -> Column {
        self.columns[i]
    }

    /// Element e of `mesh` (the mesh these sides were built on) as a shell element.
    pub fn element(&self, mesh: &SurfaceMesh, e: usize) -> ShellElement {
        self.element_of(self.columns[mesh.element_position(e).0], mesh.element(e))
    }

    /// The shell element of rectangle `rect` in `column`.
    pub fn element_of(&self, column: Column, rect: BfsRectangle) -> ShellElement {
        ShellElement { rect, alpha: column.alpha, radius: self.radius, augmented: column.augmented, gauge: 0.0 }
    }
}

/// A surface mesh on `contour` with σ-nodes on its four transitions: `per_region`
/// elements in each region (upper span, driven arc, lower span, driver arc), spaced by
/// u ↦ u + grading · u(1 − u) inside the region (0: uniform; |grading| < 1 keeps the
/// nodes increasing), and the ζ-nodes `zeta`.
///
/// # Errors
/// [`ShellError::BadParameter`] for |grading| ≥ 1 or a region without elements;
/// [`ShellError::Surface`] for the mesh's own (e.g. ζ-nodes not increasing).
pub fn contour_mesh(contour: &Contour, per_region: [usize; 4], grading: f64, zeta: Vec<f64>) -> Result<SurfaceMesh, ShellError> {
    if grading.is_nan() || grading.abs() >= 1.0 {
        return Err(ShellError::BadParameter { what: "grading", value: grading });
    }
    if let Some(&n) = per_region.iter().find(|&&n| n == 0) {
        return Err(ShellError::BadParameter { what: "elements in a region", value: n as f64 });
    }
    let t = contour.transitions();
    let ends = [t[1], t[2], t[3], contour.length()];
    let mut sigma = Vec::new();
    for (k, &n) in per_region.iter().enumerate() {
        for j in 0..n {
            let u = j as f64 / n as f64;
            sigma.push(t[k] + (ends[k] - t[k]) * (u + grading * u * (1.0 - u)));
        }
    }
    Ok(SurfaceMesh::new(contour.length(), sigma, zeta)?)
}

/// A shell element: its rectangle, α, the contour radius R and its augmented edges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShellElement {
    /// The rectangle [σ₀, σ₀ + h_σ] × [ζ₀, ζ₀ + h_ζ].
    pub rect: BfsRectangle,
    /// α of eq. (38), 1/m.
    pub alpha: f64,
    /// R (radius of the arcs to the mid-surface), m.
    pub radius: f64,
    /// Transition edges whose σ-slope terms are augmented.
    pub augmented: Augmented,
    /// c₀ of the gauge S = c₀σ + S̃ (S2) when the S unknowns are those of S̃ (the
    /// Cartesian slope in (S11) is then c₀ + ∂σS̃); 0 when they are S itself.
    pub gauge: f64,
}

impl ShellElement {
    /// The six derivative rows (f, ∂σf, ∂ζf, ∂²σf, ∂σ∂ζf, ∂²ζf) of S, ν and z at the
    /// reference point (ξ, η) from the element unknowns `q` (module order): the BFS
    /// interpolant plus, at each augmented edge, the correction (S12). Generic over the AD
    /// scalar: the values are quadratic in `q` where an edge is augmented, linear else.
    pub fn fields<D: Scalar>(&self, q: &[D; SHELL_DOFS], xi: f64, eta: f64) -> [[D; 6]; 3] {
        let weights = self.rect.derivative_weights(xi, eta);
        let mut out = [[D::zero(); 6]; 3];
        for (field, rows) in out.iter_mut().enumerate() {
            let block = &q[field * PER_FIELD..(field + 1) * PER_FIELD];
            for (row, w) in rows.iter_mut().zip(&weights) {
                *row = w.iter().zip(block).fold(D::zero(), |acc, (&wk, &qk)| acc + qk * wk);
            }
        }
        let mut terms = Vec::new();
        self.quadratic_terms(xi, eta, &mut terms);
        let local = |(field, k): (Field, usize)| slot(field) * PER_FIELD + k;
        for t in &terms {
            let factor = t.j.map_or(D::one(), |j| q[local(j)]);
            out[slot(t.field)][t.derivative as usize] += q[local(t.i)] * factor * t.coefficient;
        }
        out
    }

    /// The correction (S12) at (ξ, η) as products c q_i q_j of the element unknowns
    /// ([`QuadraticTerm`], what the surface assembler adds to the BFS point values),
    /// pushed onto `out`; nothing for an element without augmented edges.
    ///
    /// At an augmented edge with nodes a, b the correction of field X is
    /// H(ξ) g(η), g = ν_T D_C / R, with ν_T = w·(ν_a, ∂ζν_a, ν_b, ∂ζν_b) and
    /// D_C = w·(∂σX_a, ∂σ∂ζX_a, ∂σX_b, ∂σ∂ζX_b) (w the 1-D Hermite weights in ζ); its
    /// derivative of σ-order m and ζ-order k is H⁽ᵐ⁾ Σ binom(k, l) ν_T⁽ˡ⁾ D_C⁽ᵏ⁻ˡ⁾ / R, a
    /// bilinear form in the two sets of four unknowns. For S with a gauge c₀ the
    /// Cartesian slope is c₀ + D_C: the terms H⁽ᵐ⁾ ν_T⁽ᵏ⁾ c₀ / R, linear in ν, join.
    pub fn quadratic_terms(&self, xi: f64, eta: f64, out: &mut Vec<QuadraticTerm>) {
        let [h_sigma, h_zeta] = self.rect.size;
        let (vs, ds) = hermite::weights(xi, h_sigma);
        let d2s = hermite::second_weights(xi, h_sigma);
        let (vz, dz) = hermite::weights(eta, h_zeta);
        let d2z = hermite::second_weights(eta, h_zeta);
        let zeta_weights = [vz, dz, d2z];
        // (derivative row, σ-order, ζ-order), the rows of SURFACE_DERIVATIVES
        const ROWS: [(PointDerivative, usize, usize); 6] = [
            (PointDerivative::Value, 0, 0),
            (PointDerivative::DSigma, 1, 0),
            (PointDerivative::DZeta, 0, 1),
            (PointDerivative::DSigmaSigma, 2, 0),
            (PointDerivative::DSigmaZeta, 1, 1),
            (PointDerivative::DZetaZeta, 0, 2),
        ];
        // Leibniz: ∂ᵏ(ν_T D_C) = Σ_l binom(k, l) ν_T⁽ˡ⁾ D_C⁽ᵏ⁻ˡ⁾
        const LEIBNIZ: [&[(usize, usize, f64)]; 3] = [&[(0, 0, 1.0)], &[(1, 0, 1.0), (0, 1, 1.0)], &[(2, 0, 1.0), (1, 1, 2.0), (0, 2, 1.0)]];
        // (edge, the σ-slope function's index in the 1-D order, the edge's two nodes)
        for (on, slope, [a, b]) in [(self.augmented.start, 1, [0, 2]), (self.augmented.end, 3, [1, 3])] {
            if !on {
                continue;
            }
            let h = [vs[slope], ds[slope], d2s[slope]];
            // the four unknowns along the edge: ν's (value, ∂ζ) and X's (∂σ, ∂σ∂ζ) at a, b
            let nu_data = [4 * a, 4 * a + 2, 4 * b, 4 * b + 2];
            let slope_data = [4 * a + 1, 4 * a + 3, 4 * b + 1, 4 * b + 3];
            for field in FIELDS {
                for (derivative, m, k) in ROWS {
                    for &(l, r, binom) in LEIBNIZ[k] {
                        for (ki, &i) in nu_data.iter().enumerate() {
                            for (kj, &j) in slope_data.iter().enumerate() {
                                let coefficient = h[m] * binom * zeta_weights[l][ki] * zeta_weights[r][kj] / self.radius;
                                if coefficient != 0.0 {
                                    out.push(QuadraticTerm { field, derivative, i: (Field::Nu, i), j: Some((field, j)), coefficient });
                                }
                            }
                            // the gauge: the Cartesian slope of S is c₀ + ∂σS̃ (S2)
                            let gauge = h[m] * binom * zeta_weights[l][ki] * (if r == 0 { self.gauge } else { 0.0 }) / self.radius;
                            if field == Field::S && gauge != 0.0 {
                                out.push(QuadraticTerm { field, derivative, i: (Field::Nu, i), j: None, coefficient: gauge });
                            }
                        }
                    }
                }
            }
        }
    }
}

/// The shell's fields in slot order ([`S`], [`NU`], [`Z`]).
pub const FIELDS: [Field; 3] = [Field::S, Field::Nu, Field::Z];

/// The slot of a shell field in the element vector (the products of
/// [`ShellElement::quadratic_terms`] name only shell fields).
fn slot(field: Field) -> usize {
    FIELDS.iter().position(|&f| f == field).expect("a shell field")
}

/// The material derivatives (37) of the position (S1) from the point values of
/// [`ShellElement::fields`] at a point where α is `alpha`: [∂̊_s r, ∂̊_ζ r], each as its
/// components on the contour frame (t_g, n_g, k) at the point's σ —
/// ∂̊_s r = r_σ/∂σS, ∂̊_ζ r = r_ζ − (∂ζS/∂σS) r_σ with r_σ = (1 + αν, ∂σν, ∂σz) and
/// r_ζ = (0, ∂ζν, ∂ζz) (docs/fem-shell.md (S3)).
pub fn material_derivatives<D: Scalar>(alpha: f64, fields: &[[D; 6]; 3]) -> [[D; 3]; 2] {
    let (s, nu, z) = (&fields[S], &fields[NU], &fields[Z]);
    let inv = D::one() / s[1];
    let beta = s[2] * inv;
    let r_sigma = [nu[0] * alpha + 1.0, nu[1], z[1]];
    let r_zeta = [D::zero(), nu[2], z[2]];
    [r_sigma.map(|c| c * inv), std::array::from_fn(|k| r_zeta[k] - beta * r_sigma[k])]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Rng;
    use crate::element::SurfaceElement;
    use num_dual::Dual64;

    /// Nodal data per node, field and derivative (f, ∂σf, ∂ζf, ∂σ∂ζf).
    type Nodal = Vec<[[f64; 4]; 3]>;

    /// A contour of O(1) size: R = 0.3, H = 1.1.
    fn contour() -> Contour {
        Contour::new(0.3, 1.1).unwrap()
    }

    /// A mesh with σ-nodes on the four transitions: `per_region` elements per region,
    /// graded inside each region, three ζ-elements over an asymmetric width.
    fn mesh(contour: &Contour, per_region: [usize; 4]) -> SurfaceMesh {
        contour_mesh(contour, per_region, 0.15, vec![-0.2, -0.07, 0.1, 0.25]).unwrap()
    }

    /// Random nodal data of a belt near its reference state: S ≈ c₀σ with ∂σS > 0,
    /// |ν| ≤ 0.1 (a third of R: the jump of (37) without augmentation is large), z ≈ ζ, and
    /// rough ζ- and cross-derivatives.
    fn nodal(mesh: &SurfaceMesh, rng: &mut Rng) -> Nodal {
        let mut r = |scale: f64| scale * (2.0 * rng.next() - 1.0);
        let mut data = Vec::new();
        for &sigma in mesh.sigma_nodes() {
            for &zeta in mesh.zeta_nodes() {
                data.push([
                    [1.05 * sigma + r(0.05), 1.05 + r(0.3), r(0.3), r(1.0)],
                    [r(0.1), r(0.5), r(1.0), r(2.0)],
                    [zeta + r(0.05), r(0.5), 1.0 + r(0.3), r(1.0)],
                ]);
            }
        }
        data
    }

    /// The contour, a mesh of `per_region` elements per region, its columns and random
    /// nodal data from `seed`.
    fn setup(per_region: [usize; 4], seed: u64) -> (Contour, SurfaceMesh, TransitionSides, Nodal) {
        let contour = contour();
        let mesh = mesh(&contour, per_region);
        let sides = TransitionSides::new(&contour, &mesh).unwrap();
        let data = nodal(&mesh, &mut Rng(seed));
        (contour, mesh, sides, data)
    }

    /// Element e's unknowns in module order.
    fn gather(mesh: &SurfaceMesh, data: &Nodal, e: usize) -> [f64; SHELL_DOFS] {
        let nodes = mesh.element_nodes(e);
        std::array::from_fn(|k| {
            let (field, node, derivative) = (k / PER_FIELD, (k % PER_FIELD) / 4, k % 4);
            data[nodes[node]][field][derivative]
        })
    }

    /// (37) at (ξ, η) of element `el` as global 3-D vectors [∂̊_s r, ∂̊_ζ r].
    fn global_derivatives(contour: &Contour, el: &ShellElement, q: &[f64; SHELL_DOFS], xi: f64, eta: f64) -> [[f64; 3]; 2] {
        let sigma = el.rect.point(xi, eta)[0];
        let (t, n) = (contour.t_g(sigma), contour.n_g(sigma));
        material_derivatives(el.alpha, &el.fields(q, xi, eta)).map(|c| [c[0] * t[0] + c[1] * n[0], c[0] * t[1] + c[1] * n[1], c[2]])
    }

    /// Largest jump of (37) across every transition edge of the mesh over 21 η per
    /// element edge, with the elements built by `element`; and the largest |(37)|.
    fn transition_jump(contour: &Contour, mesh: &SurfaceMesh, element: &dyn Fn(usize) -> ShellElement, q_of: &dyn Fn(usize) -> [f64; SHELL_DOFS]) -> (f64, f64) {
        let (n, m) = (mesh.sigma_elements(), mesh.zeta_elements());
        let (mut jump, mut scale) = (0.0_f64, 0.0_f64);
        for i in 0..n {
            let (left, right) = ((i + n - 1) % n, i);
            let (cl, cr) = (element(left * m), element(right * m));
            if cl.alpha == cr.alpha {
                continue;
            }
            for j in 0..m {
                let (el, er) = (element(left * m + j), element(right * m + j));
                let (ql, qr) = (q_of(left * m + j), q_of(right * m + j));
                for k in 0..=20 {
                    let eta = -1.0 + 0.1 * k as f64;
                    let dl = global_derivatives(contour, &el, &ql, 1.0, eta);
                    let dr = global_derivatives(contour, &er, &qr, -1.0, eta);
                    for (a, b) in dl.iter().flatten().zip(dr.iter().flatten()) {
                        jump = jump.max((a - b).abs());
                        scale = scale.max(a.abs());
                    }
                    // the position is continuous too: S, ν, z and their ζ-derivatives
                    let (fl, fr) = (el.fields(&ql, 1.0, eta), er.fields(&qr, -1.0, eta));
                    for (a, b) in fl.iter().zip(&fr) {
                        assert!((a[0] - b[0]).abs() < 1e-12 && (a[2] - b[2]).abs() < 1e-12, "value or ∂ζ jumps at column {i}, row {j}, η = {eta}");
                    }
                }
            }
        }
        (jump, scale)
    }

    #[test]
    fn material_derivatives_are_continuous_across_every_transition_for_random_data() {
        let contour = contour();
        let mut rng = Rng(0x5eed_c1c1);
        // graded arcs of several elements, and arcs of one element (both edges augmented)
        for per_region in [[5, 4, 6, 3], [3, 1, 2, 1]] {
            let mesh = mesh(&contour, per_region);
            let sides = TransitionSides::new(&contour, &mesh).unwrap();
            let one_element_arcs = (0..mesh.sigma_elements()).filter(|&i| sides.column(i).augmented == Augmented { start: true, end: true }).count();
            assert_eq!(one_element_arcs, if per_region[1] == 1 { 2 } else { 0 });
            for _ in 0..4 {
                let data = nodal(&mesh, &mut rng);
                let element = |e: usize| sides.element(&mesh, e);
                let q_of = |e: usize| gather(&mesh, &data, e);
                let (jump, scale) = transition_jump(&contour, &mesh, &element, &q_of);
                // round-off: O(1) values from sums of a few dozen O(1) terms
                assert!(jump < 1e-12 * scale, "augmented: (37) jumps by {jump:e} (scale {scale})");
                // dropped construction: the plain BFS fields jump by O(ν/R)
                let plain = |e: usize| ShellElement { augmented: Augmented::default(), ..sides.element(&mesh, e) };
                let (jump, scale) = transition_jump(&contour, &mesh, &plain, &q_of);
                assert!(jump > 1e-3 * scale, "plain BFS: jump {jump:e} should be O(ν/R)");
            }
        }
    }

    #[test]
    fn augmented_fields_stay_c1_across_lateral_and_far_edges() {
        let (_, mesh, sides, data) = setup([4, 3, 4, 3], 0xfa2_ed9e);
        let m = mesh.zeta_elements();
        let (mut lateral, mut far, mut scale) = (0.0_f64, 0.0_f64, 0.0_f64);
        let mut compare = |a: [[f64; 6]; 3], b: [[f64; 6]; 3], worst: &mut f64| {
            for (fa, fb) in a.iter().zip(&b) {
                for row in 0..3 {
                    *worst = worst.max((fa[row] - fb[row]).abs());
                    scale = scale.max(fa[row].abs());
                }
            }
        };
        let mut checked = 0;
        for i in 0..mesh.sigma_elements() {
            let augmented = sides.column(i).augmented;
            if !(augmented.start || augmented.end) {
                continue;
            }
            checked += 1;
            for j in 0..m {
                let e = i * m + j;
                let (el, q) = (sides.element(&mesh, e), gather(&mesh, &data, e));
                for k in 0..=10 {
                    let t = -1.0 + 0.2 * k as f64;
                    // across the lateral edge to the element above
                    if j + 1 < m {
                        let (eu, qu) = (sides.element(&mesh, e + 1), gather(&mesh, &data, e + 1));
                        compare(el.fields(&q, t, 1.0), eu.fields(&qu, t, -1.0), &mut lateral);
                    }
                    // across the σ-edge that is no transition, to the polar neighbour
                    let (xi, next) = if augmented.start { (1.0, ((i + 1) % mesh.sigma_elements()) * m + j) } else { (-1.0, (i - 1) * m + j) };
                    let (en, qn) = (sides.element(&mesh, next), gather(&mesh, &data, next));
                    compare(el.fields(&q, xi, t), en.fields(&qn, -xi, t), &mut far);
                }
            }
        }
        assert_eq!(checked, 4, "two polar columns at each of the two arcs' transitions");
        assert!(lateral < 1e-12 * scale && far < 1e-12 * scale, "C¹ broken: lateral {lateral:e}, far σ-edge {far:e} (scale {scale})");
    }

    #[test]
    fn derivative_rows_match_central_differences_of_the_augmented_value() {
        let (_, mesh, sides, data) = setup([3, 1, 2, 1], 0x00c0_ffee);
        // an arc of one element: both corrections present
        let e = (0..mesh.len()).find(|&e| sides.element(&mesh, e).augmented == Augmented { start: true, end: true }).unwrap();
        let (el, q) = (sides.element(&mesh, e), gather(&mesh, &data, e));
        let [hs, hz] = el.rect.size;
        let delta = 1e-5;
        let f = |xi: f64, eta: f64| el.fields(&q, xi, eta);
        for (xi, eta) in [(-0.7, 0.3), (0.2, -0.9), (0.77, 0.55)] {
            let rows = f(xi, eta);
            let (sp, sm, zp, zm) = (f(xi + delta, eta), f(xi - delta, eta), f(xi, eta + delta), f(xi, eta - delta));
            let (ds, dz) = (hs * delta, hz * delta); // 2δ in ξ is h δ in σ
            for field in 0..3 {
                let fd = [
                    (sp[field][0] - sm[field][0]) / ds,
                    (zp[field][0] - zm[field][0]) / dz,
                    (sp[field][1] - sm[field][1]) / ds,
                    (zp[field][1] - zm[field][1]) / dz,
                    (zp[field][2] - zm[field][2]) / dz,
                ];
                let scale = rows[field].iter().fold(1.0_f64, |a, v| a.max(v.abs()));
                for (k, &row) in [1, 2, 3, 4, 5].iter().enumerate() {
                    // central differences of a polynomial: error δ²/6 × third derivative
                    assert!((rows[field][row] - fd[k]).abs() < 1e-6 * scale, "field {field} row {row}: {} vs {}", rows[field][row], fd[k]);
                }
            }
        }
    }

    #[test]
    fn augmented_fields_are_quadratic_in_the_unknowns() {
        let (_, mesh, sides, data) = setup([3, 2, 3, 2], 0x9a_d1ff);
        let mut rng = Rng(0x1d_1ec7);
        let e = (0..mesh.len()).find(|&e| sides.element(&mesh, e).augmented.end).unwrap();
        let el = sides.element(&mesh, e);
        let q = gather(&mesh, &data, e);
        let d: [f64; SHELL_DOFS] = std::array::from_fn(|_| 2.0 * rng.next() - 1.0);
        let (xi, eta) = (0.4, -0.35);
        let at = |el: &ShellElement, t: f64| el.fields(&std::array::from_fn(|k| q[k] + t * d[k]), xi, eta);
        for (el, nonlinear) in [(el, true), (ShellElement { augmented: Augmented::default(), ..el }, false)] {
            let f: Vec<[[f64; 6]; 3]> = (0..4).map(|t| at(&el, t as f64)).collect();
            let (mut third, mut second, mut scale) = (0.0_f64, 0.0_f64, 0.0_f64);
            for k in 0..18 {
                let v = |t: usize| f[t][k / 6][k % 6];
                third = third.max((v(3) - 3.0 * v(2) + 3.0 * v(1) - v(0)).abs());
                second = second.max((v(2) - 2.0 * v(1) + v(0)).abs());
                scale = scale.max(v(3).abs());
            }
            assert!(third < 1e-11 * scale, "third difference {third:e}");
            assert_eq!(second > 1e-6 * scale, nonlinear, "second difference {second:e}");
            // AD through the generic path: the directional derivative of a quadratic is its
            // central difference exactly
            let dual: [Dual64; SHELL_DOFS] = std::array::from_fn(|k| Dual64::new(q[k], d[k]));
            let g = el.fields(&dual, xi, eta);
            let (p, m) = (at(&el, 1.0), at(&el, -1.0));
            for field in 0..3 {
                for row in 0..6 {
                    let cd = 0.5 * (p[field][row] - m[field][row]);
                    assert!((g[field][row].eps - cd).abs() < 1e-11 * scale && (g[field][row].re - f[0][field][row]).abs() < 1e-13 * scale);
                }
            }
        }
    }

    #[test]
    fn columns_know_their_regions_and_refuse_transitions_off_the_nodes() {
        let contour = contour();
        let mesh = mesh(&contour, [2, 2, 2, 2]);
        let sides = TransitionSides::new(&contour, &mesh).unwrap();
        let alphas: Vec<f64> = (0..8).map(|i| sides.column(i).alpha * contour.radius()).collect();
        assert_eq!(alphas, vec![0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 1.0]);
        let starts: Vec<bool> = (0..8).map(|i| sides.column(i).augmented.start).collect();
        let ends: Vec<bool> = (0..8).map(|i| sides.column(i).augmented.end).collect();
        assert_eq!(starts, vec![false, false, true, false, false, false, true, false]);
        assert_eq!(ends, vec![false, false, false, true, false, false, false, true]);
        // a uniform mesh of 10 elements misses H = 1.1 (L_geom = 2.2 + 0.6π)
        let uniform = SurfaceMesh::mapped(contour.length(), 10, |u| u, [-0.1, 0.1], 1).unwrap();
        assert!(matches!(TransitionSides::new(&contour, &uniform), Err(ShellError::TransitionNotANode { sigma, .. }) if sigma == 1.1));
        let short = SurfaceMesh::new(contour.length() - 0.01, mesh.sigma_nodes().to_vec(), vec![0.0, 1.0]).unwrap();
        assert!(matches!(TransitionSides::new(&contour, &short), Err(ShellError::LengthMismatch { .. })));
    }

    #[test]
    fn nodal_slope_scaling_is_continuous_at_the_nodes_only() {
        // the 1-D map (K9) applied per node — polar slopes = (1 + ν/R) × Cartesian slopes
        // and their ζ-derivative — in plain BFS polar elements: exact at the nodes, not
        // between them (the product of two cubics is a sextic, docs/fem-shell.md §5)
        let (contour, mesh, sides, data) = setup([4, 3, 4, 3], 0x0dd_5eed);
        let r = contour.radius();
        let m = mesh.zeta_elements();
        let element = |e: usize| ShellElement { augmented: Augmented::default(), ..sides.element(&mesh, e) };
        let q_of = |e: usize| {
            let mut q = gather(&mesh, &data, e);
            let augmented = sides.column(e / m).augmented;
            for (on, nodes) in [(augmented.start, [0, 2]), (augmented.end, [1, 3])] {
                for node in nodes.into_iter().filter(|_| on) {
                    let (nu, nu_zeta) = (q[NU * PER_FIELD + 4 * node], q[NU * PER_FIELD + 4 * node + 2]);
                    for field in 0..3 {
                        let (slope, cross) = (q[field * PER_FIELD + 4 * node + 1], q[field * PER_FIELD + 4 * node + 3]);
                        q[field * PER_FIELD + 4 * node + 1] = (1.0 + nu / r) * slope;
                        q[field * PER_FIELD + 4 * node + 3] = nu_zeta / r * slope + (1.0 + nu / r) * cross;
                    }
                }
            }
            q
        };
        let mut at_nodes = 0.0_f64;
        for i in (0..mesh.sigma_elements()).filter(|&i| sides.column(i).augmented.start) {
            for j in 0..m {
                let (e_c, e_p) = ((i - 1) * m + j, i * m + j);
                for eta in [-1.0, 1.0] {
                    let dl = global_derivatives(&contour, &element(e_c), &q_of(e_c), 1.0, eta);
                    let dr = global_derivatives(&contour, &element(e_p), &q_of(e_p), -1.0, eta);
                    at_nodes = dl.iter().flatten().zip(dr.iter().flatten()).fold(at_nodes, |acc, (a, b)| acc.max((a - b).abs()));
                }
            }
        }
        assert!(at_nodes < 1e-12, "nodal scaling: jump {at_nodes:e} at the nodes");
        let (jump, scale) = transition_jump(&contour, &mesh, &element, &q_of);
        assert!(jump > 1e-2 * scale, "nodal scaling: jump {jump:e} between the nodes should be visible");
    }
}
