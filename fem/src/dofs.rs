//! Global numbering of the nodal unknowns, the loop closure and the material gauge
//! (docs/fem-string.md §2, §5), for any 1-D Hermite layout ([`crate::element`]).
//!
//! Node k carries, per field of the layout, its value (not s at node 0: s₀ = 0 fixes the
//! rigid sliding mode) and one slope (∂σ of the field) — two at a region transition,
//! one for the element on each side ("separate slopes"). Unknowns are numbered node by
//! node in σ order: the values (s_k (k > 0), ν_k[, θ_k]), the slopes of the element
//! ending at node k (∂σs_k⁻, ∂σν_k⁻[, ∂σθ_k⁻]), then at a transition those of the element
//! starting there (⁺; the same as ⁻ elsewhere). For the string layout {s, ν} that is
//! s_k, ν_k, ∂σs_k⁻, ∂σν_k⁻, ∂σs_k⁺, ∂σν_k⁺. Element e joins node e to node e + 1
//! (mod N); the last element ends at node 0 with s_b = s₀ + L (eq. F5), the only place
//! the belt length L enters.

use crate::element::{Dimension, ElementLayout, STRING};
use crate::kinematics::NDOF;
use crate::mesh::Mesh;

/// Most fields a 1-D layout carries ({s, ν, θ} of the Cosserat rod).
const MAX_FIELDS: usize = 3;

/// What a global unknown is (for scaling norms).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DofKind {
    /// s or ν, m.
    Value,
    /// ∂σs or ∂σν, dimensionless.
    Slope,
}

/// Indices of one node's unknowns of the string layout {s, ν}.
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

/// Indices of one node's unknowns, per field of the layout (entries past the layout's
/// field count unused).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NodeUnknowns {
    /// Value of each field (None: s at node 0, fixed to 0).
    pub values: [Option<usize>; MAX_FIELDS],
    /// ∂σ of each field for the element ending at this node.
    pub slopes_in: [usize; MAX_FIELDS],
    /// ∂σ of each field for the element starting at this node.
    pub slopes_out: [usize; MAX_FIELDS],
}

/// The map from global unknowns to each element's N local unknowns (N = the layout's
/// unknown count: 8 for the string and the Kirchhoff rod, 12 for the Cosserat rod).
#[derive(Debug, Clone, PartialEq)]
pub struct DofMap<const N: usize = NDOF> {
    layout: ElementLayout,
    nodes: Vec<NodeUnknowns>,
    kinds: Vec<DofKind>,
    /// Node spacing per unknown (for slope residual scaling), m.
    spacing: Vec<f64>,
    elements: Vec<[Option<usize>; N]>,
    /// The last element ends at node 0 (a loop): its s_b carries the closure offset L.
    closed: bool,
}

impl DofMap {
    /// The numbering of a mesh with separate slope pairs at the transitions (the string).
    pub fn new(mesh: &Mesh) -> DofMap {
        DofMap::with_transition_slopes(mesh, true)
    }

    /// The numbering of a string-layout mesh; `separate` = two slope pairs at each
    /// transition (the string, docs/fem-string.md §5), else one shared pair: the primary
    /// slopes of the Cartesian side, from which the polar side's follow by the augmented
    /// map (K9) of docs/fem-rod.md §3 (the rod; 4N − 1 unknowns).
    pub fn with_transition_slopes(mesh: &Mesh, separate: bool) -> DofMap {
        DofMap::with_layout(mesh, STRING, separate)
    }

    /// The unknowns of node k (string layout).
    pub fn node(&self, k: usize) -> NodeDofs {
        let n = &self.nodes[k];
        NodeDofs {
            s: n.values[0],
            nu: n.values[1].expect("ν is an unknown at every node"),
            slopes_in: (n.slopes_in[0], n.slopes_in[1]),
            slopes_out: (n.slopes_out[0], n.slopes_out[1]),
        }
    }
}

impl<const N: usize> DofMap<N> {
    /// The numbering of a mesh for the 1-D Hermite `layout` (N = `layout.dofs()`; the
    /// first field is the material coordinate s); `separate` as in
    /// [`DofMap::with_transition_slopes`].
    ///
    /// # Panics
    /// If the layout is not 1-D, has more than three fields or N is not its unknown
    /// count (a programming error: the layouts are constants).
    pub fn with_layout(mesh: &Mesh, layout: ElementLayout, separate: bool) -> DofMap<N> {
        assert!(layout.dimension == Dimension::One && layout.fields.len() <= MAX_FIELDS && layout.dofs() == N, "DofMap<{N}> with layout {layout:?}");
        let fields = layout.fields.len();
        // N nodes on a loop, N + 1 on an open mesh (docs/fem-cosserat.md §12.1)
        let n = mesh.node_count();
        let open_end = |k: usize| mesh.is_open() && (k == 0 || k + 1 == n);
        let mut nodes = Vec::with_capacity(n);
        let mut kinds = Vec::with_capacity(2 * fields * n + 4 * fields);
        let mut spacing = Vec::with_capacity(2 * fields * n + 4 * fields);
        let mut push = |kind: DofKind, h: f64| {
            kinds.push(kind);
            spacing.push(h);
            kinds.len() - 1
        };
        for k in 0..n {
            let h = mesh.node_spacing(k);
            let mut node = NodeUnknowns { values: [None; MAX_FIELDS], slopes_in: [0; MAX_FIELDS], slopes_out: [0; MAX_FIELDS] };
            for f in 0..fields {
                // s₀ = 0 (the gauge); on an open mesh the fields after s and ν (the
                // rotation ψ) are essential at both ends (θ prescribed, §12.2)
                node.values[f] = ((k > 0 || f > 0) && !(f > 1 && open_end(k))).then(|| push(DofKind::Value, h));
            }
            for f in 0..fields {
                node.slopes_in[f] = push(DofKind::Slope, h);
            }
            node.slopes_out = node.slopes_in;
            if separate && mesh.is_transition(k) {
                for f in 0..fields {
                    node.slopes_out[f] = push(DofKind::Slope, h);
                }
            }
            nodes.push(node);
        }
        let elements = (0..mesh.len())
            .map(|e| {
                let (a, b) = (&nodes[e], &nodes[(e + 1) % n]);
                let mut idx = [None; N];
                for f in 0..fields {
                    idx[layout.index(0, f, 0)] = a.values[f];
                    idx[layout.index(0, f, 1)] = Some(a.slopes_out[f]);
                    idx[layout.index(1, f, 0)] = b.values[f];
                    idx[layout.index(1, f, 1)] = Some(b.slopes_in[f]);
                }
                idx
            })
            .collect();
        DofMap { layout, nodes, kinds, spacing, elements, closed: !mesh.is_open() }
    }

    /// The element layout.
    pub fn layout(&self) -> ElementLayout {
        self.layout
    }

    /// Number of global unknowns (string: 4N + 7 with separate transition slopes, else
    /// 4N − 1).
    pub fn len(&self) -> usize {
        self.kinds.len()
    }

    /// Never true; for clippy.
    pub fn is_empty(&self) -> bool {
        self.kinds.is_empty()
    }

    /// The unknowns of node k, per field.
    pub fn node_unknowns(&self, k: usize) -> &NodeUnknowns {
        &self.nodes[k]
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
    pub fn element(&self, e: usize) -> &[Option<usize>; N] {
        &self.elements[e]
    }

    /// Element e's local unknowns from the global vector z and the belt length L
    /// (the closure offset of the last element's s_b, eq. F5; not used on an open mesh).
    #[inline]
    pub fn gather(&self, e: usize, z: &[f64], length: f64) -> [f64; N] {
        let idx = &self.elements[e];
        let mut q: [f64; N] = std::array::from_fn(|i| idx[i].map_or(0.0, |g| z[g]));
        if self.closed && e + 1 == self.elements.len() {
            q[self.layout.index(1, 0, 0)] += length;
        }
        q
    }
}

/// Per element, whether the augmented map (docs/fem-rod.md §3, K9) applies at its start
/// and end node: only with shared transition slopes (`separate = false`), on a polar
/// element, at a node that is a region transition.
pub fn augmented_flags(mesh: &Mesh, separate: bool) -> Vec<[bool; 2]> {
    mesh.elements()
        .iter()
        .enumerate()
        .map(|(e, g)| {
            let on = !separate && g.region.is_polar();
            [on && mesh.is_transition(e), on && mesh.is_transition((e + 1) % mesh.node_count())]
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

    /// The Cosserat layout {s, ν, θ}: 3N − 1 values (s₀ fixed) and 3N slopes plus 3 per
    /// transition; neighbours share every field's value, and its slope except at a
    /// transition; the closure offset lands on the last element's s_b (local index 6).
    #[test]
    fn cosserat_layout_numbering() {
        use crate::element::COSSERAT;
        let c = Contour::new(0.08, 0.45).unwrap();
        let n = 12;
        let mesh = Mesh::new(c, n, 1.0).unwrap();
        let map = DofMap::<12>::with_layout(&mesh, COSSERAT, true);
        assert_eq!(map.len(), 6 * n - 1 + 3 * 4);
        assert_eq!(map.kinds().iter().filter(|k| **k == DofKind::Value).count(), 3 * n - 1);
        for e in 0..n {
            let (a, b) = (map.element(e), map.element((e + 1) % n));
            for f in 0..3 {
                assert_eq!(a[COSSERAT.index(1, f, 0)], b[COSSERAT.index(0, f, 0)]);
                let shared = a[COSSERAT.index(1, f, 1)] == b[COSSERAT.index(0, f, 1)];
                assert_eq!(shared, !mesh.is_transition((e + 1) % n), "element {e} field {f}");
            }
        }
        let q = map.gather(n - 1, &vec![0.0; map.len()], 1.5);
        assert_eq!(q[COSSERAT.index(1, 0, 0)], 1.5);
        assert_eq!(q.iter().filter(|v| **v != 0.0).count(), 1);
    }

    /// The open mesh of the one-pulley layout (docs/fem-cosserat.md §12.1): N + 1 nodes,
    /// no closure offset, ψ essential at both ends, every unknown used, neighbours
    /// sharing their node's values and slopes.
    #[test]
    fn open_numbering() {
        use crate::element::COSSERAT;
        let c = Contour::new(0.1, 0.5).unwrap();
        for n in [4, 9, 64] {
            let mesh = Mesh::open(c, n, 1.0).unwrap();
            assert_eq!(mesh.node_count(), n + 1);
            assert!((mesh.end_sigma() - (1.0 + std::f64::consts::PI * 0.1)).abs() < 1e-15);
            let map: DofMap<12> = DofMap::with_layout(&mesh, COSSERAT, false);
            // 6 per node, less s₀ and the two end values of ψ
            assert_eq!(map.len(), 6 * (n + 1) - 3);
            assert!(map.node_unknowns(0).values[2].is_none() && map.node_unknowns(n).values[2].is_none());
            assert!(map.node_unknowns(n).values[0].is_some());
            let mut used = vec![false; map.len()];
            for e in 0..n {
                map.element(e).iter().flatten().for_each(|g| used[*g] = true);
            }
            assert!(used.iter().all(|&u| u));
            for e in 0..n - 1 {
                let (a, b) = (map.element(e), map.element(e + 1));
                for f in 0..3 {
                    assert_eq!(a[COSSERAT.index(1, f, 0)], b[COSSERAT.index(0, f, 0)]);
                    assert_eq!(a[COSSERAT.index(1, f, 1)], b[COSSERAT.index(0, f, 1)]);
                }
            }
            // no closure: the last element's s_b is its node's value, whatever L
            let z: Vec<f64> = (0..map.len()).map(|i| i as f64).collect();
            assert_eq!(map.gather(n - 1, &z, 7.0), map.gather(n - 1, &z, 0.0));
        }
    }
}
