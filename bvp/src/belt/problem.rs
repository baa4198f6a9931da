//! The one belt BVP: a [`Topology`] of segments and a [`SectionLaw`] make a
//! multi-segment [`Problem`] in standard form.
//!
//! Right-hand sides: a span asks the law with its span parameter, an arc with its polar
//! angle φ = φ_a + Δφ ξ and Δφ = φ_b − φ_a. Conditions, in this order: the junction that
//! closes the loop (the belt leaves the last arc into segment 0), then the junction at
//! the end of each segment 0, 1, …, m − 2, then the law's loop conditions. The closure
//! jump of a frictionless loop is added at the driver's first contact.

use crate::problem::{Problem, Scalar};

use super::law::{Rows, SectionLaw};
use super::topology::{Junction, Pulley, Scaling, SegmentKind, Topology};

/// A belt problem: the topology and the section law (scaled, along its homotopy path).
#[derive(Debug, Clone)]
pub struct BeltProblem<L> {
    /// The segments.
    pub topology: Topology,
    /// The belt theory.
    pub law: L,
}

impl<L: SectionLaw> BeltProblem<L> {
    /// The problem of `law` on `topology`.
    pub fn new(topology: Topology, law: L) -> Self {
        Self { topology, law }
    }

    fn arc_kind(&self, k: usize) -> crate::belt::topology::ArcKind {
        match self.topology.segment(k).kind {
            SegmentKind::Arc(kind) => kind,
            SegmentKind::Span => unreachable!("segment {k} is a span"),
        }
    }
}

impl<L: SectionLaw> Problem for BeltProblem<L> {
    fn n_segments(&self) -> usize {
        self.topology.len()
    }

    fn dim(&self, k: usize) -> usize {
        self.law.state_names(self.topology.segment(k).kind).len()
    }

    fn n_params(&self) -> usize {
        self.topology.n_params() + self.law.extra_params().len()
    }

    fn rhs<D: Scalar>(&self, k: usize, x: f64, y: &[D], p: &[D], eta: D, f: &mut [D]) {
        let topo = &self.topology;
        match topo.segment(k).scaling {
            Scaling::Span { param } => self.law.span_rhs(topo, p[param], y, p, eta, f),
            Scaling::Arc { pulley, start, end } => {
                let dphi = p[end] - p[start];
                let phi = p[start] + dphi * x;
                self.law.arc_rhs(topo, self.arc_kind(k), pulley, phi, dphi, y, p, eta, f);
            }
        }
    }

    fn bc<D: Scalar>(&self, ya: &[&[D]], yb: &[&[D]], p: &[D], eta: D, r: &mut [D]) {
        let topo = &self.topology;
        let m = topo.len();
        let mut rows = Rows::new(r);
        for (next, &start) in ya.iter().enumerate() {
            let k = (next + m - 1) % m;
            match topo.junction(k) {
                Junction::MidSpan => self.law.mid_span(yb[k], start, &mut rows),
                Junction::ContactStart { pulley, angle } => {
                    let jump = topo.closure_jump().filter(|_| pulley == Pulley::Driver).map(|i| p[i]);
                    self.law.contact_start(self.arc_kind(next), pulley, p[angle], yb[k], start, jump, p, eta, &mut rows);
                }
                Junction::ArcToArc { pulley, .. } => self.law.arc_to_arc(pulley, yb[k], start, p, &mut rows),
                Junction::ContactEnd { pulley, angle, closes_loop } => {
                    self.law.contact_end(pulley, p[angle], yb[k], start, closes_loop, p, eta, &mut rows);
                }
            }
        }
        self.law.loop_conditions(topo, ya, yb, p, eta, &mut rows);
        debug_assert_eq!(rows.written(), self.n_bc(), "one condition per unknown");
    }

    fn component_names(&self, k: usize) -> Vec<String> {
        self.law.state_names(self.topology.segment(k).kind).iter().map(|s| s.to_string()).collect()
    }

    fn param_names(&self) -> Vec<String> {
        let mut names = self.topology.param_names().to_vec();
        names.extend(self.law.extra_params().iter().map(|s| s.to_string()));
        names
    }
}
