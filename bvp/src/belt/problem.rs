//! The one belt BVP: a [`Topology`] of segments and a [`SectionLaw`] make a
//! multi-segment [`Problem`] in standard form.
//!
//! Right-hand sides: a span asks the law with its span parameter, an arc with its polar
//! angle φ = φ_a + Δφ ξ and Δφ = φ_b − φ_a. Conditions, in this order: the junction that
//! closes the loop (the belt leaves the last arc into segment 0) — on an open topology
//! the end conditions of the inflow and outflow ends instead — then the junction at
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
    /// Per segment: the parameters its right-hand side reads, ascending (its own span
    /// length or arc angles and the law's [`SectionLaw::rhs_reads`]).
    rhs_params: Vec<Vec<usize>>,
}

impl<L: SectionLaw> BeltProblem<L> {
    /// The problem of `law` on `topology`.
    pub fn new(topology: Topology, law: L) -> Self {
        let reads = law.rhs_reads(&topology);
        let rhs_params = topology
            .segments()
            .iter()
            .map(|seg| {
                let mut params = reads.clone();
                match seg.scaling {
                    Scaling::Span { param } => params.push(param),
                    Scaling::Arc { start, end, .. } => params.extend([start, end]),
                }
                params.sort_unstable();
                params.dedup();
                params
            })
            .collect();
        Self { topology, law, rhs_params }
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

    fn rhs_params(&self, k: usize) -> Option<&[usize]> {
        Some(&self.rhs_params[k])
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
                Junction::OpenEnds => self.law.open_ends(start, yb[k], p, eta, &mut rows),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::belt::topology::ContactModel;
    use crate::jacobian::rhs_jacobian;
    use crate::problem::JacobianMode;
    use crate::rod_hanging::law::ScaledRodHanging;
    use crate::string_drive::law::ScaledStringDrive;
    use crate::string_hanging::law::ScaledStringHanging;

    /// The same problem without its declared parameter dependence: every column of
    /// ∂f/∂p is evaluated.
    struct EveryParam<'a, P>(&'a P);

    impl<P: Problem> Problem for EveryParam<'_, P> {
        fn n_segments(&self) -> usize {
            self.0.n_segments()
        }
        fn dim(&self, k: usize) -> usize {
            self.0.dim(k)
        }
        fn n_params(&self) -> usize {
            self.0.n_params()
        }
        fn rhs<D: Scalar>(&self, k: usize, x: f64, y: &[D], p: &[D], eta: D, f: &mut [D]) {
            self.0.rhs(k, x, y, p, eta, f)
        }
        fn bc<D: Scalar>(&self, ya: &[&[D]], yb: &[&[D]], p: &[D], eta: D, r: &mut [D]) {
            self.0.bc(ya, yb, p, eta, r)
        }
    }

    /// Every segment's Jacobian with the declared parameters equals the one with every
    /// column evaluated, bit for bit, in both Jacobian modes: no law reads a parameter it
    /// did not declare (a missed one would show as a nonzero column left out).
    fn declared_params_are_complete<L: SectionLaw>(problem: &BeltProblem<L>, eta: f64) {
        let np = problem.n_params();
        let p: Vec<f64> = (0..np).map(|i| 0.3 + 0.17 * i as f64).collect();
        for k in 0..problem.n_segments() {
            let n = problem.dim(k);
            let y: Vec<f64> = (0..n).map(|i| 0.8 + 0.23 * i as f64).collect();
            let declared = problem.rhs_params(k).expect("a belt problem declares its parameters");
            assert!(declared.len() < np, "segment {k} declares all {np} parameters");
            for mode in [JacobianMode::Ad, JacobianMode::FiniteDifference] {
                let cheap = rhs_jacobian(problem, mode, k, 0.4, &y, &p, eta);
                let full = rhs_jacobian(&EveryParam(problem), mode, k, 0.4, &y, &p, eta);
                assert_eq!(cheap, full, "segment {k}, {mode:?}: a parameter outside {declared:?} is read");
            }
        }
    }

    #[test]
    fn every_law_declares_the_parameters_it_reads() {
        let string = ScaledStringHanging { radius: 0.18, axial_stiffness: 50.0, weight: 0.7, length_start: 3.0, length: 3.2 };
        declared_params_are_complete(&BeltProblem::new(Topology::two_pulley(ContactModel::Frictionless), string), 0.6);
        let rod = ScaledRodHanging { radius: 0.18, axial_stiffness: 50.0, weight: 0.7, length: 3.2, bending_start: 1e-3, bending: 2e-2 };
        declared_params_are_complete(&BeltProblem::new(Topology::two_pulley(ContactModel::Frictionless), rod), 0.6);
        for (inertia, weight) in [(true, 0.7), (false, 0.0)] {
            let drive = ScaledStringDrive::fixture(inertia, weight);
            declared_params_are_complete(&BeltProblem::new(Topology::two_pulley(ContactModel::Coulomb), drive), 0.6);
        }
        let pulley = crate::cosserat_pulley::ScaledCosseratPulley {
            axial: 600.0,
            shear: 70.0,
            chi: 0.03,
            bending_start: 0.05,
            bending: 0.07,
            end_distance: 5.0,
            end_forces: [0.97, 0.64],
            mu: 0.3,
            slip_sign: 1.0,
            free_end: None,
            closing: crate::cosserat_pulley::Closing::None,
        };
        declared_params_are_complete(&BeltProblem::new(Topology::one_pulley(), pulley.clone()), 0.6);
        let speed = crate::cosserat_pulley::ScaledCosseratPulley { free_end: Some(0), closing: crate::cosserat_pulley::Closing::StickStretch(1.01), ..pulley };
        declared_params_are_complete(&BeltProblem::new(Topology::one_pulley(), speed), 0.6);
    }
}
