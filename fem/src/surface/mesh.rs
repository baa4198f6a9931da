//! The structured mesh over the mid-surface: n_σ elements around the closed loop
//! σ ∈ [0, L) (periodic: element i joins σ-nodes i and i + 1 mod n_σ, the last one ends at
//! σ = L ≡ 0) times n_ζ elements across the width ζ ∈ [ζ₀, ζ₁] (open: free or
//! constrained edges). Spacing may be non-uniform in both directions. Element e = i n_ζ + j
//! is the flat [`BfsRectangle`] [σ_i, σ_{i+1}] × [ζ_j, ζ_{j+1}]; node (i, j) is number
//! i (n_ζ + 1) + j.

use crate::element::BfsRectangle;

use super::SurfaceError;

/// Fewest elements around the loop (a σ-node must not be its own neighbour, and the
/// history interpolation needs four distinct points per row).
pub const MIN_SIGMA_ELEMENTS: usize = 4;

/// A structured (σ periodic) × (ζ open) mesh of Bogner–Fox–Schmit rectangles.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceMesh {
    length: f64,
    /// σ of the n_σ nodes, strictly increasing in [0, L).
    sigma: Vec<f64>,
    /// ζ of the n_ζ + 1 nodes, strictly increasing.
    zeta: Vec<f64>,
}

impl SurfaceMesh {
    /// The mesh with σ-nodes `sigma` (first 0, strictly increasing, below `length`) and
    /// ζ-nodes `zeta` (strictly increasing; the first and last are the edges).
    ///
    /// # Errors
    /// [`SurfaceError::BadLength`], [`SurfaceError::TooFewElements`] (fewer than
    /// [`MIN_SIGMA_ELEMENTS`] around the loop or none across), [`SurfaceError::BadNode`].
    pub fn new(length: f64, sigma: Vec<f64>, zeta: Vec<f64>) -> Result<SurfaceMesh, SurfaceError> {
        if !(length.is_finite() && length > 0.0) {
            return Err(SurfaceError::BadLength { what: "loop length L", value: length });
        }
        if sigma.len() < MIN_SIGMA_ELEMENTS {
            return Err(SurfaceError::TooFewElements { direction: "σ", elements: sigma.len(), minimum: MIN_SIGMA_ELEMENTS });
        }
        if zeta.len() < 2 {
            return Err(SurfaceError::TooFewElements { direction: "ζ", elements: zeta.len().saturating_sub(1), minimum: 1 });
        }
        let increasing = |direction: &'static str, v: &[f64], low: f64, high: f64| {
            for (index, &value) in v.iter().enumerate() {
                let above = if index == 0 { value >= low } else { value > v[index - 1] };
                if !(value.is_finite() && above && value <= high) {
                    return Err(SurfaceError::BadNode { direction, index, value, low, high });
                }
            }
            Ok(())
        };
        if sigma[0] != 0.0 {
            return Err(SurfaceError::BadNode { direction: "σ", index: 0, value: sigma[0], low: 0.0, high: 0.0 });
        }
        increasing("σ", &sigma, 0.0, length * (1.0 - f64::EPSILON))?;
        increasing("ζ", &zeta, f64::NEG_INFINITY, f64::INFINITY)?;
        Ok(SurfaceMesh { length, sigma, zeta })
    }

    /// Nodes σ_i = L m(i/n_σ) and ζ_j = ζ₀ + (ζ₁ − ζ₀) j/n_ζ, with a monotone map m of
    /// [0, 1] onto itself (the identity for a uniform mesh).
    ///
    /// # Errors
    /// As [`SurfaceMesh::new`] (a map that is not increasing gives [`SurfaceError::BadNode`]).
    pub fn mapped(length: f64, n_sigma: usize, map: impl Fn(f64) -> f64, width: [f64; 2], n_zeta: usize) -> Result<SurfaceMesh, SurfaceError> {
        if width[1] - width[0] <= 0.0 || (width[1] - width[0]).is_nan() {
            return Err(SurfaceError::BadLength { what: "width ζ₁ − ζ₀", value: width[1] - width[0] });
        }
        let sigma = (0..n_sigma).map(|i| if i == 0 { 0.0 } else { length * map(i as f64 / n_sigma as f64) }).collect();
        let zeta = (0..=n_zeta).map(|j| if j == n_zeta { width[1] } else { width[0] + (width[1] - width[0]) * j as f64 / n_zeta as f64 }).collect();
        SurfaceMesh::new(length, sigma, zeta)
    }

    /// Loop length L, m.
    pub fn length(&self) -> f64 {
        self.length
    }

    /// σ of the σ-nodes.
    pub fn sigma_nodes(&self) -> &[f64] {
        &self.sigma
    }

    /// ζ of the ζ-nodes (edges first and last).
    pub fn zeta_nodes(&self) -> &[f64] {
        &self.zeta
    }

    /// Elements around the loop, n_σ (= σ-nodes).
    pub fn sigma_elements(&self) -> usize {
        self.sigma.len()
    }

    /// Elements across the width, n_ζ.
    pub fn zeta_elements(&self) -> usize {
        self.zeta.len() - 1
    }

    /// Elements, n_σ n_ζ.
    pub fn len(&self) -> usize {
        self.sigma_elements() * self.zeta_elements()
    }

    /// Never true; for clippy.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Nodes, n_σ (n_ζ + 1).
    pub fn nodes(&self) -> usize {
        self.sigma.len() * self.zeta.len()
    }

    /// Node number of σ-node i (mod n_σ) and ζ-node j.
    pub fn node(&self, i: usize, j: usize) -> usize {
        (i % self.sigma.len()) * self.zeta.len() + j
    }

    /// (i, j) of element e.
    pub fn element_position(&self, e: usize) -> (usize, usize) {
        (e / self.zeta_elements(), e % self.zeta_elements())
    }

    /// Element e's nodes in BFS order: (σ_i, ζ_j), (σ_{i+1}, ζ_j), (σ_i, ζ_{j+1}),
    /// (σ_{i+1}, ζ_{j+1}), σ-index mod n_σ.
    pub fn element_nodes(&self, e: usize) -> [usize; 4] {
        let (i, j) = self.element_position(e);
        [self.node(i, j), self.node(i + 1, j), self.node(i, j + 1), self.node(i + 1, j + 1)]
    }

    /// Element e as a rectangle (the last σ-element ends at σ = L).
    pub fn element(&self, e: usize) -> BfsRectangle {
        let (i, j) = self.element_position(e);
        let end = if i + 1 == self.sigma.len() { self.length } else { self.sigma[i + 1] };
        BfsRectangle { origin: [self.sigma[i], self.zeta[j]], size: [end - self.sigma[i], self.zeta[j + 1] - self.zeta[j]] }
    }

    /// The element holding (σ, ζ) (σ taken mod L, ζ clamped to the width) and the
    /// reference point (ξ, η) there.
    pub fn locate(&self, sigma: f64, zeta: f64) -> (usize, f64, f64) {
        let s = sigma.rem_euclid(self.length);
        let i = self.sigma.partition_point(|&x| x <= s).saturating_sub(1);
        let j = self.zeta.partition_point(|&x| x <= zeta).saturating_sub(1).min(self.zeta_elements() - 1);
        let e = i * self.zeta_elements() + j;
        let el = self.element(e);
        let xi = 2.0 * (s - el.origin[0]) / el.size[0] - 1.0;
        let eta = (2.0 * (zeta - el.origin[1]) / el.size[1] - 1.0).clamp(-1.0, 1.0);
        (e, xi, eta)
    }

    /// The mesh with every element split in two in each direction (refinement ratio 2).
    pub fn refined(&self) -> SurfaceMesh {
        let split = |v: &[f64], end: Option<f64>| {
            let mut out = Vec::with_capacity(2 * v.len());
            for (k, &a) in v.iter().enumerate() {
                out.push(a);
                if let Some(b) = v.get(k + 1).copied().or(end) {
                    out.push(0.5 * (a + b));
                }
            }
            out
        };
        SurfaceMesh { length: self.length, sigma: split(&self.sigma, Some(self.length)), zeta: split(&self.zeta, None) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::SurfaceElement;

    #[test]
    fn periodic_elements_close_the_loop_and_locate_points() {
        let mesh = SurfaceMesh::mapped(2.0, 6, |u| u + 0.3 * (std::f64::consts::TAU * u).sin() / std::f64::consts::TAU, [-0.1, 0.1], 3).unwrap();
        assert_eq!((mesh.len(), mesh.nodes()), (18, 24));
        // the last σ-column of elements ends at L and shares the σ-nodes 0
        let last = mesh.element(17);
        assert!((last.origin[0] + last.size[0] - 2.0).abs() < 1e-15);
        assert_eq!(mesh.element_nodes(17)[1], mesh.node(0, 2));
        assert_eq!(mesh.element_nodes(17)[3], mesh.node(0, 3));
        let total: f64 = (0..6).map(|i| mesh.element(3 * i).size[0]).sum();
        assert!((total - 2.0).abs() < 1e-14);
        // locate gives back the point, also across the wrap
        for (s, z) in [(0.0, -0.1), (1.999, 0.1), (2.3, 0.03), (-0.4, -0.05)] {
            let (e, xi, eta) = mesh.locate(s, z);
            let [ps, pz] = mesh.element(e).point(xi, eta);
            assert!((ps - s.rem_euclid(2.0)).abs() < 1e-13 && (pz - z).abs() < 1e-15, "({s}, {z}) → element {e} at ({ps}, {pz})");
        }
        let fine = mesh.refined();
        assert_eq!((fine.sigma_elements(), fine.zeta_elements()), (12, 6));
        assert_eq!(fine.sigma_nodes()[2], mesh.sigma_nodes()[1]);
        assert!((fine.sigma_nodes()[11] - 0.5 * (mesh.sigma_nodes()[5] + 2.0)).abs() < 1e-15);
        // refusals
        assert!(matches!(SurfaceMesh::new(1.0, vec![0.0, 0.5, 0.4, 0.9], vec![0.0, 1.0]), Err(SurfaceError::BadNode { index: 2, .. })));
        assert!(matches!(SurfaceMesh::new(1.0, vec![0.0, 0.5, 0.7], vec![0.0, 1.0]), Err(SurfaceError::TooFewElements { direction: "σ", .. })));
        assert!(matches!(SurfaceMesh::new(1.0, vec![0.0, 0.2, 0.5, 1.0], vec![0.0, 1.0]), Err(SurfaceError::BadNode { index: 3, .. })));
        assert!(matches!(SurfaceMesh::new(1.0, vec![0.0, 0.2, 0.5, 0.7], vec![0.0]), Err(SurfaceError::TooFewElements { direction: "ζ", .. })));
    }
}
