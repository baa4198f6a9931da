//! Numbering of the Bogner–Fox–Schmit unknowns on a [`SurfaceMesh`]: per node and per
//! field a kernel uses, the four nodal unknowns f, ∂σf, ∂ζf, ∂σ∂ζf (physical
//! derivatives, the BFS order of [`crate::element`]). Numbered node by node (node
//! i (n_ζ + 1) + j), then field, then derivative; σ-node n_σ is σ-node 0 (the loop is
//! closed, so every field is periodic in σ with its derivatives). An [`EdgeConstraint`]
//! fixes one nodal unknown to zero along an edge ζ = ζ₀ or ζ₁ (e.g. a simply supported
//! edge: f = ∂σf = 0); fixed unknowns have no number.
//!
//! An element's local vector holds the used fields one after the other, each in the
//! per-field order of the shape weights ([`crate::element::ElementLayout::field_indices`]:
//! node-major, then derivative): local index `16 · slot + 4 · node + derivative`.

use crate::element::{Dimension, ElementLayout, Field};

use super::mesh::SurfaceMesh;
use super::SurfaceError;

/// Unknowns of one field on one element (4 nodes × 4 nodal derivatives).
pub const PER_FIELD: usize = 16;

/// A derivative of a surface field: the rows of
/// [`crate::element::BfsRectangle::derivative_weights`] (what a kernel reads at a point,
/// `as usize`); the first three and ∂σ∂ζf are also the BFS nodal unknowns
/// ([`PointDerivative::nodal`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointDerivative {
    /// f.
    Value = 0,
    /// ∂σf.
    DSigma = 1,
    /// ∂ζf.
    DZeta = 2,
    /// ∂²σf.
    DSigmaSigma = 3,
    /// ∂σ∂ζf.
    DSigmaZeta = 4,
    /// ∂²ζf.
    DZetaZeta = 5,
}

impl PointDerivative {
    /// The nodal unknowns of a BFS field, in element order (f, ∂σf, ∂ζf, ∂σ∂ζf).
    pub const NODAL: [PointDerivative; 4] = [PointDerivative::Value, PointDerivative::DSigma, PointDerivative::DZeta, PointDerivative::DSigmaZeta];

    /// Position among the nodal unknowns; None for ∂²σf and ∂²ζf (no unknowns of their own).
    pub fn nodal(self) -> Option<usize> {
        PointDerivative::NODAL.iter().position(|&d| d == self)
    }
}

/// One of the two edges of the width.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ZetaEdge {
    /// ζ = ζ₀.
    Lower,
    /// ζ = ζ₁.
    Upper,
}

/// A nodal unknown fixed to zero at every node of an edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EdgeConstraint {
    /// The edge.
    pub edge: ZetaEdge,
    /// The field.
    pub field: Field,
    /// The unknown (one of [`PointDerivative::NODAL`]).
    pub nodal: PointDerivative,
}

/// A nodal unknown fixed to zero at one node: σ-node `sigma_node`, ζ-node `zeta_node`.
/// Meant for one unknown of a zero mode of the energy (a rigid translation, the gauge
/// of a material coordinate): the gradient along the mode vanishes identically, so at an
/// equilibrium of the other unknowns the fixed one carries no reaction
/// (docs/fem-shell.md §9.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NodeConstraint {
    /// σ-node index (0 … n_σ − 1).
    pub sigma_node: usize,
    /// ζ-node index (0 … n_ζ).
    pub zeta_node: usize,
    /// The field.
    pub field: Field,
    /// The unknown (one of [`PointDerivative::NODAL`]).
    pub nodal: PointDerivative,
}

/// The numbering of the used fields' unknowns on a surface mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceDofMap {
    layout: ElementLayout,
    fields: Vec<Field>,
    /// Per node, used field and nodal derivative: the global number (None: fixed).
    nodes: Vec<Option<usize>>,
    /// Per element its local unknowns' numbers, `fields.len() · 16` each.
    elements: Vec<Option<usize>>,
    len: usize,
}

impl SurfaceDofMap {
    /// The numbering of `fields` (each carried by the 2-D `layout`; numbered in layout
    /// order) on `mesh`, with the unknowns of `fixed` removed.
    ///
    /// # Errors
    /// [`SurfaceError::BadKernel`]: a layout that is not 2-D, a field it does not carry,
    /// no field, or a constraint on a field not numbered.
    pub fn new(mesh: &SurfaceMesh, layout: ElementLayout, fields: &[Field], fixed: &[EdgeConstraint]) -> Result<SurfaceDofMap, SurfaceError> {
        SurfaceDofMap::with_nodes(mesh, layout, fields, fixed, &[])
    }

    /// [`Self::new`] with the single-node constraints `nodes` besides the edge
    /// constraints `fixed`.
    ///
    /// # Errors
    /// As [`Self::new`]; [`SurfaceError::BadKernel`] also for a node constraint off the
    /// mesh or on a field not numbered.
    pub fn with_nodes(mesh: &SurfaceMesh, layout: ElementLayout, fields: &[Field], fixed: &[EdgeConstraint], nodes_fixed: &[NodeConstraint]) -> Result<SurfaceDofMap, SurfaceError> {
        let bad = |reason: String| SurfaceError::BadKernel { layout: format!("{:?}", layout.fields), reason };
        if layout.dimension != Dimension::Two {
            return Err(bad("not a 2-D layout".into()));
        }
        if let Some(f) = fields.iter().find(|f| layout.position(**f).is_none()) {
            return Err(bad(format!("no field {f:?}")));
        }
        if let Some(c) = fixed.iter().find(|c| !fields.contains(&c.field) || c.nodal.nodal().is_none()) {
            return Err(bad(format!("constraint on {:?} {:?}, which is not a numbered nodal unknown", c.field, c.nodal)));
        }
        if let Some(c) = nodes_fixed.iter().find(|c| !fields.contains(&c.field) || c.nodal.nodal().is_none() || c.sigma_node >= mesh.sigma_elements() || c.zeta_node > mesh.zeta_elements()) {
            return Err(bad(format!("node constraint on {:?} {:?} at node ({}, {}), which is not a numbered nodal unknown of the mesh", c.field, c.nodal, c.sigma_node, c.zeta_node)));
        }
        let used: Vec<Field> = layout.fields.iter().copied().filter(|f| fields.contains(f)).collect();
        if used.is_empty() {
            return Err(bad("no field used".into()));
        }
        let nf = used.len();
        let top = mesh.zeta_elements();
        let mut nodes = vec![None; mesh.nodes() * nf * 4];
        let mut len = 0;
        for i in 0..mesh.sigma_elements() {
            for j in 0..=top {
                for (slot, field) in used.iter().enumerate() {
                    for (k, d) in PointDerivative::NODAL.into_iter().enumerate() {
                        let held = fixed.iter().any(|c| {
                            let on = match c.edge {
                                ZetaEdge::Lower => j == 0,
                                ZetaEdge::Upper => j == top,
                            };
                            on && c.field == *field && c.nodal == d
                        }) || nodes_fixed.iter().any(|c| c.sigma_node == i && c.zeta_node == j && c.field == *field && c.nodal == d);
                        if !held {
                            nodes[(mesh.node(i, j) * nf + slot) * 4 + k] = Some(len);
                            len += 1;
                        }
                    }
                }
            }
        }
        let mut elements = Vec::with_capacity(mesh.len() * nf * PER_FIELD);
        for e in 0..mesh.len() {
            let corners = mesh.element_nodes(e);
            for slot in 0..nf {
                for node in corners {
                    elements.extend_from_slice(&nodes[(node * nf + slot) * 4..(node * nf + slot + 1) * 4]);
                }
            }
        }
        Ok(SurfaceDofMap { layout, fields: used, nodes, elements, len })
    }

    /// The element layout.
    pub fn layout(&self) -> ElementLayout {
        self.layout
    }

    /// The numbered fields, in layout order (their slot is the position here).
    pub fn fields(&self) -> &[Field] {
        &self.fields
    }

    /// Slot of `field`, if numbered.
    pub fn slot(&self, field: Field) -> Option<usize> {
        self.fields.iter().position(|&f| f == field)
    }

    /// Global unknowns.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True without unknowns (never, for a valid map).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Local unknowns of an element: 16 per used field.
    pub fn local_len(&self) -> usize {
        self.fields.len() * PER_FIELD
    }

    /// The global numbers of element e's local unknowns (None: fixed to zero).
    pub fn element(&self, e: usize) -> &[Option<usize>] {
        let n = self.local_len();
        &self.elements[e * n..(e + 1) * n]
    }

    /// The number of a node's unknown of the field in `slot` (None: fixed, or not a
    /// nodal unknown).
    pub fn node_unknown(&self, node: usize, slot: usize, nodal: PointDerivative) -> Option<usize> {
        self.nodes[(node * self.fields.len() + slot) * 4 + nodal.nodal()?]
    }

    /// The global vector of `to` (a numbering of the same mesh and fields, with other
    /// constraints) holding the values of `z` (numbered by `self`); unknowns fixed here
    /// are 0 there.
    ///
    /// # Errors
    /// [`SurfaceError::BadKernel`] if the two numberings differ in fields or nodes, or
    /// `z` is not numbered by `self`.
    pub fn transfer(&self, z: &[f64], to: &SurfaceDofMap) -> Result<Vec<f64>, SurfaceError> {
        if self.fields != to.fields || self.nodes.len() != to.nodes.len() || z.len() != self.len {
            return Err(SurfaceError::BadKernel { layout: format!("{:?}", self.layout.fields), reason: format!("transfer of {} values between numberings of {:?} ({} slots) and {:?} ({} slots)", z.len(), self.fields, self.nodes.len(), to.fields, to.nodes.len()) });
        }
        let mut out = vec![0.0; to.len];
        for (from, into) in self.nodes.iter().zip(&to.nodes) {
            if let (Some(a), Some(b)) = (from, into) {
                out[*b] = z[*a];
            }
        }
        Ok(out)
    }

    /// Element e's local unknowns from the global vector z (0 where fixed).
    pub fn gather(&self, e: usize, z: &[f64]) -> Vec<f64> {
        self.element(e).iter().map(|g| g.map_or(0.0, |g| z[g])).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::SHELL;

    /// Neighbours share their common nodes' unknowns, also across the loop closure;
    /// constraints remove exactly their unknowns; each unknown belongs to some element.
    #[test]
    fn numbering_is_periodic_in_sigma_and_honours_edge_constraints() {
        let mesh = SurfaceMesh::mapped(1.0, 5, |u| u, [0.0, 0.2], 2).unwrap();
        let fixed = [
            EdgeConstraint { edge: ZetaEdge::Lower, field: Field::Nu, nodal: PointDerivative::Value },
            EdgeConstraint { edge: ZetaEdge::Upper, field: Field::Nu, nodal: PointDerivative::DSigma },
        ];
        let map = SurfaceDofMap::new(&mesh, SHELL, &[Field::Z, Field::Nu], &fixed).unwrap();
        assert_eq!(map.fields(), &[Field::Nu, Field::Z]);
        assert_eq!(map.len(), 15 * 2 * 4 - 2 * 5);
        assert_eq!(map.local_len(), 32);
        let mut used = vec![false; map.len()];
        for e in 0..mesh.len() {
            for g in map.element(e).iter().flatten() {
                used[*g] = true;
            }
        }
        assert!(used.iter().all(|&u| u));
        // element (4, j) ends on σ-node 0: its nodes 1, 3 are element (0, j)'s nodes 0, 2
        for j in 0..2 {
            let (last, first) = (map.element(4 * 2 + j), map.element(j));
            for slot in 0..2 {
                for d in 0..4 {
                    assert_eq!(last[16 * slot + 4 + d], first[16 * slot + d]);
                    assert_eq!(last[16 * slot + 12 + d], first[16 * slot + 8 + d]);
                }
            }
        }
        // ν at ζ₀ has no value unknown, ν at ζ₁ no ∂σ; z keeps all
        assert_eq!(map.node_unknown(mesh.node(3, 0), 0, PointDerivative::Value), None);
        assert!(map.node_unknown(mesh.node(3, 0), 0, PointDerivative::DSigma).is_some());
        assert_eq!(map.node_unknown(mesh.node(3, 2), 0, PointDerivative::DSigma), None);
        assert!(map.node_unknown(mesh.node(3, 0), 1, PointDerivative::Value).is_some());
        assert!(matches!(SurfaceDofMap::new(&mesh, SHELL, &[Field::Theta], &[]), Err(SurfaceError::BadKernel { .. })));
        let second = EdgeConstraint { edge: ZetaEdge::Lower, field: Field::Nu, nodal: PointDerivative::DZetaZeta };
        assert!(matches!(SurfaceDofMap::new(&mesh, SHELL, &[Field::Nu], &[second]), Err(SurfaceError::BadKernel { .. })));
        assert!(matches!(SurfaceDofMap::new(&mesh, crate::element::STRING, &[Field::Nu], &[]), Err(SurfaceError::BadKernel { .. })));
    }

    /// A node constraint removes exactly its one unknown; a transfer to the
    /// unconstrained numbering puts every value where it was and 0 at the fixed one, and
    /// back again; constraints off the mesh and mismatched transfers are refused.
    #[test]
    fn node_constraints_remove_one_unknown_and_transfer_keeps_values() {
        let mesh = SurfaceMesh::mapped(1.0, 5, |u| u, [0.0, 0.2], 2).unwrap();
        let fields = [Field::Nu, Field::Z];
        let pin = [NodeConstraint { sigma_node: 3, zeta_node: 1, field: Field::Z, nodal: PointDerivative::Value }];
        let free = SurfaceDofMap::new(&mesh, SHELL, &fields, &[]).unwrap();
        let held = SurfaceDofMap::with_nodes(&mesh, SHELL, &fields, &[], &pin).unwrap();
        assert_eq!(held.len(), free.len() - 1);
        let node = mesh.node(3, 1);
        assert_eq!(held.node_unknown(node, 1, PointDerivative::Value), None);
        assert!(held.node_unknown(node, 1, PointDerivative::DSigma).is_some() && held.node_unknown(node, 0, PointDerivative::Value).is_some());
        assert!(held.node_unknown(mesh.node(3, 0), 1, PointDerivative::Value).is_some());
        let z: Vec<f64> = (0..held.len()).map(|i| 1.0 + i as f64).collect();
        let wide = held.transfer(&z, &free).unwrap();
        assert_eq!(wide[free.node_unknown(node, 1, PointDerivative::Value).unwrap()], 0.0);
        assert_eq!(wide.iter().filter(|&&v| v == 0.0).count(), 1);
        assert_eq!(free.transfer(&wide, &held).unwrap(), z);
        for e in 0..mesh.len() {
            assert_eq!(held.gather(e, &z), free.gather(e, &wide));
        }
        let off = NodeConstraint { sigma_node: 5, zeta_node: 0, field: Field::Z, nodal: PointDerivative::Value };
        assert!(matches!(SurfaceDofMap::with_nodes(&mesh, SHELL, &fields, &[], &[off]), Err(SurfaceError::BadKernel { .. })));
        let unused = NodeConstraint { field: Field::S, ..pin[0] };
        assert!(matches!(SurfaceDofMap::with_nodes(&mesh, SHELL, &fields, &[], &[unused]), Err(SurfaceError::BadKernel { .. })));
        let other = SurfaceDofMap::new(&mesh, SHELL, &[Field::Nu], &[]).unwrap();
        assert!(matches!(held.transfer(&z, &other), Err(SurfaceError::BadKernel { .. })));
        assert!(matches!(held.transfer(&z[1..], &free), Err(SurfaceError::BadKernel { .. })));
    }
}
