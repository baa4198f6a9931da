//! Global numbering of the nodal unknowns, the loop closure and the material gauge
//! (docs/fem-string.md §2, §5).
//!
//! Node k carries s_k (not node 0: s₀ = 0 fixes the rigid sliding mode), ν_k, and one
//! slope pair (∂σs, ∂σν) — two at a region transition, one for the element on each side
//! ("separate slopes"). Unknowns are numbered node by node in σ order:
//! s_k (k > 0), ν_k, ∂σs_k⁻, ∂σν_k⁻, then ∂σs_k⁺, ∂σν_k⁺ at a transition, where ⁻ is the
//! pair used by the element ending at node k and ⁺ the pair of the element starting
//! there (the same pair except at transitions). Element e joins node e to node e + 1 (mod N); the last element ends
//! at node 0 with s_b = s₀ + L (eq. F5), the only place the belt length L enters.

use crate::kinematics::NDOF;
use crate::mesh::Mesh;

/// What a global unknown is (for scaling norms).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DofKind {
    /// s or ν, m.
    Value,
    /// ∂σs or ∂σν, dimensionless.
    Slope,
}

/// Indices of one node's unknowns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NodeDofs {
    /// s (None at node 0: fixed to 0).
    pub s: Option<usize>,
    /// ν.
    pub nu: usize,
    /// (∂σs, ∂σν) of the element ending at this node.
    pub slopes_in: (usize, usize),
    /// (∂σs, ∂σν) of the element starting at this node.
    pub slopes_out: (usize, usize),
}

/// The map from global unknowns to each element's 8 local unknowns.
#[derive(Debug, Clone, PartialEq)]
pub struct DofMap {
    nodes: Vec<NodeDofs>,
    kinds: Vec<DofKind>,
    /// Node spacing per unknown (for slope residual scaling), m.
    spacing: Vec<f64>,
    elements: Vec<[Option<usize>; NDOF]>,
}

impl DofMap {
    /// The numbering of a mesh with separate slope pairs at the transitions (the string).
    pub fn new(mesh: &Mesh) -> DofMap {
        DofMap::with_transition_slopes(mesh, true)
    }

    /// The numbering of a mesh; `separate` = two slope pairs at each transition (the
    /// string, docs/fem-string.md §5), else one shared pair: the primary slopes of the
    /// Cartesian side, from which the polar side's follow by the augmented map (K9) of
    /// docs/fem-rod.md §3 (the rod; 4N − 1 unknowns).
    pub fn with_transition_slopes(mesh: &Mesh, separate: bool) -> DofMap {
        let n = mesh.len();
        let mut nodes = Vec::with_capacity(n);
        let mut kinds = Vec::with_capacity(4 * n + 8);
        let mut spacing = Vec::with_capacity(4 * n + 8);
        let mut next = 0usize;
        let mut push = |kind: DofKind, h: f64, kinds: &mut Vec<DofKind>, spacing: &mut Vec<f64>| {
            kinds.push(kind);
            spacing.push(h);
            next += 1;
            next - 1
        };
        for k in 0..n {
            let h = mesh.node_spacing(k);
            let s = (k > 0).then(|| push(DofKind::Value, h, &mut kinds, &mut spacing));
            let nu = push(DofKind::Value, h, &mut kinds, &mut spacing);
            let slopes_in = (
                push(DofKind::Slope, h, &mut kinds, &mut spacing),
                push(DofKind::Slope, h, &mut kinds, &mut spacing),
            );
            let slopes_out = if separate && mesh.is_transition(k) {
                (
                    push(DofKind::Slope, h, &mut kinds, &mut spacing),
                    push(DofKind::Slope, h, &mut kinds, &mut spacing),
                )
            } else {
                slopes_in
            };
            nodes.push(NodeDofs { s, nu, slopes_in, slopes_out });
        }
        let elements = (0..n)
            .map(|e| {
                let a = nodes[e];
                let b = nodes[(e + 1) % n];
                [
                    a.s,
                    Some(a.slopes_out.0),
                    Some(a.nu),
                    Some(a.slopes_out.1),
                    b.s,
                    Some(b.slopes_in.0),
                    Some(b.nu),
                    Some(b.slopes_in.1),
                ]
            })
            .collect();
        DofMap { nodes, kinds, spacing, elements }
    }

    /// Number of global unknowns (4N + 7 with separate transition slopes, else 4N − 1).
    pub fn len(&self) -> usize {
        self.kinds.len()
    }

    /// Never true; for clippy.
    pub fn is_empty(&self) -> bool {
        self.kinds.is_empty()
    }

    /// The unknowns of node k.
    pub fn node(&self, k: usize) -> NodeDofs {
        self.nodes[k]
    }

    /// Kind of each global unknown.
    pub fn kinds(&self) -> &[DofKind] {
        &self.kinds
    }

    /// Mean element length at the node of each global unknown, m.
    pub fn spacing(&self) -> &[f64] {
        &self.spacing
    }

    /// Global indices of element e's local unknowns (None = the fixed s₀).
    pub fn element(&self, e: usize) -> &[Option<usize>; NDOF] {
        &self.elements[e]
    }

    /// Element e's local unknowns from the global vector z and the belt length L
    /// (the closure offset of the last element, eq. F5).
    #[inline]
    pub fn gather(&self, e: usize, z: &[f64], length: f64) -> [f64; NDOF] {
        let idx = &self.elements[e];
        let mut q: [f64; NDOF] = std::array::from_fn(|i| idx[i].map_or(0.0, |g| z[g]));
        if e + 1 == self.elements.len() {
            q[4] += length;
        }
        q
    }
}

/// Per element, whether the augmented map (docs/fem-rod.md §3, K9) applies at its start
/// and end node: only with shared transition slopes (`separate = false`), on a polar
/// element, at a node that is a region transition.
pub fn augmented_flags(mesh: &Mesh, separate: bool) -> Vec<[bool; 2]> {
    let n = mesh.len();
    mesh.elements()
        .iter()
        .enumerate()
        .map(|(e, g)| {
            let on = !separate && g.region.is_polar();
            [on && mesh.is_transition(e), on && mesh.is_transition((e + 1) % n)]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use drive::contour::Contour;

    #[test]
    fn numbering_and_closure() {
        let c = Contour::new(0.08, 0.45).unwrap();
        for n in [4, 9, 64] {
            let mesh = Mesh::new(c, n, 1.0).unwrap();
            let map = DofMap::new(&mesh);
            assert_eq!(map.len(), 4 * n + 7);
            // every unknown is used by some element
            let mut used = vec![false; map.len()];
            for e in 0..n {
                for g in map.element(e).iter().flatten() {
                    used[*g] = true;
                }
            }
            assert!(used.iter().all(|&u| u));
            // shared values between neighbours, separate slopes at transitions
            for e in 0..n {
                let a = map.element(e);
                let b = map.element((e + 1) % n);
                assert_eq!(a[4], b[0]);
                assert_eq!(a[6], b[2]);
                let k = (e + 1) % n;
                if mesh.is_transition(k) {
                    assert_ne!(a[5], b[1]);
                    assert_ne!(a[7], b[3]);
                } else {
                    assert_eq!(a[5], b[1]);
                    assert_eq!(a[7], b[3]);
                }
            }
            assert_eq!(map.element(0)[0], None);
            // closure: a linear s(σ) = σ L/L_c is gathered consistently
            let l = 1.5;
            let mut z = vec![0.0; map.len()];
            for k in 0..n {
                let nd = map.node(k);
                if let Some(s) = nd.s {
                    z[s] = mesh.node_sigmas()[k] * l / c.length();
                }
                z[nd.slopes_in.0] = l / c.length();
                z[nd.slopes_out.0] = l / c.length();
            }
            let q = map.gather(n - 1, &z, l);
            assert!((q[4] - l).abs() < 1e-15);
            assert!((q[0] - mesh.node_sigmas()[n - 1] * l / c.length()).abs() < 1e-15);
        }
    }
}
