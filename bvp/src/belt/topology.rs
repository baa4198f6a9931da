//! The segment topology of a belt BVP: which segments, in which order, what kind each is
//! (free span, contact arc frictionless / stick / slip), on which side of the loop (for
//! the σ map), on which pulley, and which unknown parameters scale them.
//!
//! The topology knows nothing of a belt theory: the [`SectionLaw`](super::law::SectionLaw)
//! supplies the states, right-hand sides and conditions of each segment and junction it
//! names. Built from the scene's layout and effects ([`Topology::from_scene`]).
//!
//! The two-pulley loop (today's only layout) runs in the direction of σ from the point
//! where the belt leaves the driver:
//!
//! | frictionless (6 segments) | Coulomb friction (8 segments) |
//! |---|---|
//! | upper span to x = 0, upper span to the driven pulley, driven arc, lower span to x = 0, lower span to the driver, driver arc | the same with each arc split into stick then slip |
//!
//! The spans are split at x = 0 so that the mid-span values are node values.
//!
//! Parameters, in this order: the span parameters (one per span, in segment order; the
//! law decides what it is — the string and the Kirchhoff rod integrate in s and read it
//! as the unstretched span length), the contact angles of each pulley in segment order
//! (first contact φ_a, stick → slip φ_t with friction, last contact φ_b), then
//! - on frictionless pulleys the closure jump f: the frictionless loop has a first
//!   integral, which makes one condition redundant; f is the tension jump at the
//!   driver's first contact that restores a square system (0 for the exact solution);
//! - with friction the motion: transport rate c and driven pulley speed ω₂,
//!
//! and last the law's own parameters ([`SectionLaw::extra_params`](super::law::SectionLaw::extra_params); none for the
//! string and the Kirchhoff rod, λ₁, λ₂ for the Cosserat drive).

use std::f64::consts::FRAC_PI_2;

use drive::scene::{Contact, Scene};

pub use crate::sigma_map::Side;
pub use drive::contour::Direction;

/// A pulley of the two-pulley drive, or the single pulley of the open one-pulley
/// layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pulley {
    /// The driver (left, centre at x = −H/2).
    Driver,
    /// The driven pulley (right, centre at x = +H/2).
    Driven,
    /// The one pulley of the open layout (centre at the origin; the belt arrives along
    /// its upper side in +x and leaves along its lower side in −x, as on the driven
    /// pulley of the loop).
    Single,
}

impl Pulley {
    /// Centre x-coordinate in units of H: driver −½, driven +½.
    pub fn centre_x(self) -> f64 {
        match self {
            Pulley::Driver => -0.5,
            Pulley::Driven => 0.5,
            Pulley::Single => 0.0,
        }
    }

    /// "driver" or "driven".
    pub fn name(self) -> &'static str {
        match self {
            Pulley::Driver => "driver",
            Pulley::Driven => "driven",
            Pulley::Single => "pulley",
        }
    }

    /// The contact angles of the tight contour (first contact, last contact), rad,
    /// unwrapped as the BVP uses them: driven (π/2, −π/2), driver (−π/2, −3π/2).
    pub fn tight_angles(self) -> (f64, f64) {
        match self {
            Pulley::Driven | Pulley::Single => (FRAC_PI_2, -FRAC_PI_2),
            Pulley::Driver => (-FRAC_PI_2, -3.0 * FRAC_PI_2),
        }
    }

    /// Slip sign κ of the Coulomb law on this pulley (docs/string-drive.md, "Both
    /// rotation senses and both power flows"): the friction on the belt in the slip zone
    /// is τ = κμp along σ. The pulley that puts power into the belt drags it in its
    /// direction of travel (τ along the travel), the other brakes it: κ = ±1 with the sign
    /// of (travel along σ) × (this pulley puts power in). Clockwise with the driver
    /// driving: +1 on the driver (the belt is slower than the pulley), −1 on the driven.
    pub fn slip_sign(self, direction: Direction, flow: PowerFlow) -> f64 {
        let puts_power_in = match (self, flow) {
            (Pulley::Driver, PowerFlow::FromDriver) | (Pulley::Driven, PowerFlow::FromDriven) => 1.0,
            _ => -1.0,
        };
        direction.sign() * puts_power_in
    }
}

/// Which pulley puts power into the belt (docs/string-drive.md, "Both rotation senses
/// and both power flows").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PowerFlow {
    /// The driver drives, the driven pulley's net load M₂ + d₂ω₂ resists its motion.
    FromDriver,
    /// The load drives the driven pulley (M₂ + d₂ω₂ of the sense of ω₂ opposite to a
    /// resisting load), the driver brakes.
    FromDriven,
}

impl PowerFlow {
    /// The power flow of a net driven load `load` = M₂ + d₂ω₁ (N·m, the clockwise torque
    /// the belt must exert on the driven pulley) in `direction`: from the driver when
    /// the load resists the motion or vanishes.
    pub fn of_load(load: f64, direction: Direction) -> Self {
        if load * direction.sign() < 0.0 { PowerFlow::FromDriven } else { PowerFlow::FromDriver }
    }
}

/// The kind of a contact arc.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArcKind {
    /// No tangential force.
    Frictionless,
    /// Coulomb friction, no relative motion.
    Stick,
    /// Coulomb friction, sliding.
    Slip,
}

/// The kind of a segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SegmentKind {
    /// A free span.
    Span,
    /// A contact arc.
    Arc(ArcKind),
}

/// What scales a segment's normalised interval ξ ∈ [0, 1].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scaling {
    /// A span: parameter index of its span parameter.
    Span { param: usize },
    /// An arc from polar angle p[start] to p[end] on `pulley`.
    Arc { pulley: Pulley, start: usize, end: usize },
}

/// One segment of the topology.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Segment {
    /// Span or arc kind.
    pub kind: SegmentKind,
    /// Side of the loop for the σ map.
    pub side: Side,
    /// Its parameters.
    pub scaling: Scaling,
}

impl Segment {
    /// The pulley of an arc; `None` for a span.
    pub fn pulley(&self) -> Option<Pulley> {
        match self.scaling {
            Scaling::Arc { pulley, .. } => Some(pulley),
            Scaling::Span { .. } => None,
        }
    }
}

/// The junction at the end of a segment (between segment k and k + 1, the last one
/// closing the loop to segment 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Junction {
    /// Between the two halves of a span (the split at x = 0).
    MidSpan,
    /// A span meets a pulley: first contact at angle p[angle].
    ContactStart { pulley: Pulley, angle: usize },
    /// Two arcs on one pulley (stick → slip) at angle p[angle].
    ArcToArc { pulley: Pulley, angle: usize },
    /// The belt leaves a pulley at angle p[angle]; `closes_loop` at the end of the last
    /// segment (the material coordinate restarts at 0 and the tangent angle gains 2π).
    ContactEnd { pulley: Pulley, angle: usize, closes_loop: bool },
    /// The end of the last segment of an open topology: no junction, the inflow end
    /// (start of segment 0) and the outflow end (end of the last segment) carry the
    /// law's end conditions instead.
    OpenEnds,
}

/// The contact model of the pulleys, as the topology sees it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactModel {
    /// One frictionless arc per pulley.
    Frictionless,
    /// Coulomb friction: a stick arc then a slip arc on each pulley (steady drive).
    Coulomb,
}

/// Parameter indices of the motion of a steady drive.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Motion {
    /// Transport rate c.
    pub transport: usize,
    /// Driven pulley speed ω₂.
    pub driven_speed: usize,
}

/// Why no topology can be built from a scene.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TopologyError {
    /// The contact model has no segment topology in the BVP (the elastic interlayer).
    #[error("contact model {0} has no BVP segment topology")]
    UnsupportedContact(String),
}

/// The ordered segments of a belt BVP and its topology parameters (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Topology {
    segments: Vec<Segment>,
    param_names: Vec<String>,
    closure_jump: Option<usize>,
    motion: Option<Motion>,
    direction: Direction,
    open: bool,
}

impl Topology {
    /// The closed two-pulley loop with `contact` on both pulleys (module docs), the belt
    /// running clockwise.
    pub fn two_pulley(contact: ContactModel) -> Self {
        Self::two_pulley_running(contact, Direction::Clockwise)
    }

    /// The closed two-pulley loop with `contact` on both pulleys, the belt running in
    /// `direction`. The segments always follow σ; with friction the stick arc is where
    /// the belt runs onto a pulley, so along σ each pulley has stick → slip running
    /// clockwise and slip → stick running counter-clockwise (docs/string-drive.md, "Both
    /// rotation senses and both power flows"). The angle between the two arcs is φ_t,
    /// the last contact φ_b, whatever the arcs' kinds.
    pub fn two_pulley_running(contact: ContactModel, direction: Direction) -> Self {
        use Side::{Arc, LowerSpan, UpperSpan};
        let arcs: &[ArcKind] = match (contact, direction) {
            (ContactModel::Frictionless, _) => &[ArcKind::Frictionless],
            (ContactModel::Coulomb, Direction::Clockwise) => &[ArcKind::Stick, ArcKind::Slip],
            (ContactModel::Coulomb, Direction::CounterClockwise) => &[ArcKind::Slip, ArcKind::Stick],
        };
        // (kind, side, pulley) in loop order.
        let mut order: Vec<(SegmentKind, Side, Option<Pulley>)> = vec![(SegmentKind::Span, UpperSpan, None); 2];
        order.extend(arcs.iter().map(|&a| (SegmentKind::Arc(a), Arc, Some(Pulley::Driven))));
        order.extend([(SegmentKind::Span, LowerSpan, None); 2]);
        order.extend(arcs.iter().map(|&a| (SegmentKind::Arc(a), Arc, Some(Pulley::Driver))));

        let mut names = Vec::new();
        let mut scalings = vec![None; order.len()];
        for (k, (kind, _, _)) in order.iter().enumerate() {
            if *kind == SegmentKind::Span {
                scalings[k] = Some(Scaling::Span { param: names.len() });
                names.push(format!("l{k}"));
            }
        }
        let mut last_angle: Option<(Pulley, usize)> = None;
        for (k, &(kind, _, pulley)) in order.iter().enumerate() {
            let (SegmentKind::Arc(_), Some(pulley)) = (kind, pulley) else { continue };
            let number = if pulley == Pulley::Driver { 1 } else { 2 };
            let start = match last_angle {
                Some((p, i)) if p == pulley => i,
                _ => {
                    names.push(format!("phi{number}a"));
                    names.len() - 1
                }
            };
            let last_on_pulley = order.get(k + 1).is_none_or(|next| next.2 != Some(pulley));
            let end_name = if last_on_pulley { "b" } else { "t" };
            names.push(format!("phi{number}{end_name}"));
            let end = names.len() - 1;
            scalings[k] = Some(Scaling::Arc { pulley, start, end });
            last_angle = Some((pulley, end));
        }
        let (closure_jump, motion) = match contact {
            ContactModel::Frictionless => {
                names.push("defect".into());
                (Some(names.len() - 1), None)
            }
            ContactModel::Coulomb => {
                names.push("c".into());
                names.push("omega2".into());
                (None, Some(Motion { transport: names.len() - 2, driven_speed: names.len() - 1 }))
            }
        };
        let segments = order
            .iter()
            .zip(scalings)
            .map(|(&(kind, side, _), scaling)| Segment { kind, side, scaling: scaling.expect("every segment is scaled") })
            .collect();
        Self { segments, param_names: names, closure_jump, motion, direction, open: false }
    }

    /// The open one-pulley layout (spec §2.4): inflow span, stick arc, slip arc, outflow
    /// span on [`Pulley::Single`], the belt running clockwise. Parameters: the two span
    /// parameters `l0`, `l3`, then the contact angles `phi_a` (first contact), `phi_t`
    /// (stick → slip), `phi_b` (last contact); no closure jump and no motion (the
    /// transport rate is given); the law's own parameters follow.
    pub fn one_pulley() -> Self {
        let span = |param, side| Segment { kind: SegmentKind::Span, side, scaling: Scaling::Span { param } };
        let arc = |kind, start, end| Segment { kind: SegmentKind::Arc(kind), side: Side::Arc, scaling: Scaling::Arc { pulley: Pulley::Single, start, end } };
        let segments = vec![span(0, Side::UpperSpan), arc(ArcKind::Stick, 2, 3), arc(ArcKind::Slip, 3, 4), span(1, Side::LowerSpan)];
        let param_names = ["l0", "l3", "phi_a", "phi_t", "phi_b"].map(String::from).to_vec();
        Self { segments, param_names, closure_jump: None, motion: None, direction: Direction::Clockwise, open: true }
    }

    /// True for an open topology (the one-pulley layout): its last segment ends in
    /// [`Junction::OpenEnds`].
    pub fn is_open(&self) -> bool {
        self.open
    }

    /// The pulleys the topology's arcs lie on, in order of first appearance.
    pub fn pulleys(&self) -> Vec<Pulley> {
        let mut out: Vec<Pulley> = Vec::new();
        for p in self.segments.iter().filter_map(Segment::pulley) {
            if !out.contains(&p) {
                out.push(p);
            }
        }
        out
    }

    /// The topology of a scene: its layout (the two-pulley loop), its contact effect and
    /// the running direction of its driver.
    pub fn from_scene(scene: &Scene) -> Result<Self, TopologyError> {
        let direction = Direction::of_speed(scene.drive.driver_speed);
        match scene.effects.contact {
            Contact::Frictionless => Ok(Self::two_pulley(ContactModel::Frictionless)),
            Contact::Coulomb(_) => Ok(Self::two_pulley_running(ContactModel::Coulomb, direction)),
            ref other => Err(TopologyError::UnsupportedContact(format!("{other:?}"))),
        }
    }

    /// The running direction of the belt.
    pub fn direction(&self) -> Direction {
        self.direction
    }

    /// The segments in loop order.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// Segment `k`.
    pub fn segment(&self, k: usize) -> &Segment {
        &self.segments[k]
    }

    /// Number of segments.
    pub fn len(&self) -> usize {
        self.segments.len()
    }

    /// Never true: a topology has segments.
    pub fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }

    /// True when segment `k` is a free span.
    pub fn is_span(&self, k: usize) -> bool {
        self.segments[k].kind == SegmentKind::Span
    }

    /// The sides of the segments for the σ map.
    pub fn sides(&self) -> Vec<Side> {
        self.segments.iter().map(|s| s.side).collect()
    }

    /// Number of topology parameters (the law's own come after them).
    pub fn n_params(&self) -> usize {
        self.param_names.len()
    }

    /// Names of the topology parameters.
    pub fn param_names(&self) -> &[String] {
        &self.param_names
    }

    /// Parameter index of the closure jump f (frictionless loop).
    pub fn closure_jump(&self) -> Option<usize> {
        self.closure_jump
    }

    /// Parameter indices of the motion (drive with friction).
    pub fn motion(&self) -> Option<Motion> {
        self.motion
    }

    /// True when the arcs carry Coulomb friction (stick and slip).
    pub fn has_friction(&self) -> bool {
        self.segments.iter().any(|s| matches!(s.kind, SegmentKind::Arc(ArcKind::Stick | ArcKind::Slip)))
    }

    /// The junction at the end of segment `k`.
    pub fn junction(&self, k: usize) -> Junction {
        let m = self.segments.len();
        if self.open && k + 1 == m {
            return Junction::OpenEnds;
        }
        let (here, next) = (&self.segments[k], &self.segments[(k + 1) % m]);
        match (here.scaling, next.scaling) {
            (Scaling::Span { .. }, Scaling::Span { .. }) => Junction::MidSpan,
            (Scaling::Span { .. }, Scaling::Arc { pulley, start, .. }) => Junction::ContactStart { pulley, angle: start },
            (Scaling::Arc { pulley, end, .. }, Scaling::Arc { .. }) => Junction::ArcToArc { pulley, angle: end },
            (Scaling::Arc { pulley, end, .. }, Scaling::Span { .. }) => {
                Junction::ContactEnd { pulley, angle: end, closes_loop: k + 1 == m }
            }
        }
    }

    /// The arc segments of `pulley`, in loop order.
    pub fn arcs_on(&self, pulley: Pulley) -> Vec<usize> {
        (0..self.segments.len()).filter(|&k| self.segments[k].pulley() == Some(pulley)).collect()
    }

    /// The first arc segment on `pulley` (where the belt arrives).
    pub fn first_arc(&self, pulley: Pulley) -> usize {
        self.arcs_on(pulley)[0]
    }

    /// The last arc segment on `pulley` (where the belt leaves).
    pub fn last_arc(&self, pulley: Pulley) -> usize {
        *self.arcs_on(pulley).last().expect("every pulley has an arc")
    }

    /// The arc segment of `kind` on `pulley`, if the topology has one.
    pub fn arc(&self, pulley: Pulley, kind: ArcKind) -> Option<usize> {
        self.arcs_on(pulley).into_iter().find(|&k| self.segments[k].kind == SegmentKind::Arc(kind))
    }

    /// Parameter index of the stick ↔ slip angle of `pulley` (`phi1t`, `phi2t`: the
    /// junction between its two arcs) in either running direction; `None` on a pulley
    /// with a single arc (frictionless).
    pub fn transition_angle(&self, pulley: Pulley) -> Option<usize> {
        match self.junction(self.first_arc(pulley)) {
            Junction::ArcToArc { angle, .. } => Some(angle),
            _ => None,
        }
    }

    /// The span segments whose end is the mid-span point x = 0: (upper, lower).
    pub fn mid_spans(&self) -> (usize, usize) {
        let mid = |side: Side| {
            (0..self.segments.len())
                .find(|&k| self.segments[k].side == side && self.junction(k) == Junction::MidSpan)
                .expect("the two-pulley loop splits each span at x = 0")
        };
        (mid(Side::UpperSpan), mid(Side::LowerSpan))
    }

    /// The span before the first arc of `pulley` and the span after its last arc.
    pub fn spans_around(&self, pulley: Pulley) -> (usize, usize) {
        let m = self.segments.len();
        ((self.first_arc(pulley) + m - 1) % m, (self.last_arc(pulley) + 1) % m)
    }

    /// Contact angles (first contact, [stick → slip,] last contact) of `pulley` from
    /// the parameter vector, rad, unwrapped.
    pub fn contact_angles(&self, pulley: Pulley, p: &[f64]) -> Vec<f64> {
        let arcs = self.arcs_on(pulley);
        let mut out = Vec::new();
        for k in arcs {
            if let Scaling::Arc { start, end, .. } = self.segments[k].scaling {
                if out.is_empty() {
                    out.push(p[start]);
                }
                out.push(p[end]);
            }
        }
        out
    }

    /// Whether parameters `p` describe this topology (the acceptance test of every
    /// homotopy point and of the final solution): each first/last contact angle within
    /// `window` (rad) of its tight-contour value, each arc of length ≥ −`slack` (rad),
    /// every span parameter > 0 and a transport rate in the running direction
    /// (c ≥ −1e-12 clockwise, c ≤ 1e-12 counter-clockwise). The discrete equations
    /// have unphysical solutions (a belt wound once more round a pulley, at an enormous
    /// tension); this test keeps the homotopy and the final solve off them.
    // The negated comparisons are deliberate: a NaN parameter must fail these checks.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    pub fn check(&self, p: &[f64], window: f64, slack: f64) -> Result<(), String> {
        for pulley in self.pulleys() {
            let (first, last) = (self.first_arc(pulley), self.last_arc(pulley));
            let (tight_a, tight_b) = pulley.tight_angles();
            let (Scaling::Arc { start, .. }, Scaling::Arc { end, .. }) = (self.segments[first].scaling, self.segments[last].scaling)
            else {
                unreachable!("arcs are scaled by angles")
            };
            for (what, i, tight) in [("first", start, tight_a), ("last", end, tight_b)] {
                if !((p[i] - tight).abs() < window) {
                    return Err(format!(
                        "{what} contact on the {} pulley at {:.2}° is more than {:.0}° from its tight-contour value {:.0}°",
                        pulley.name(),
                        p[i].to_degrees(),
                        window.to_degrees(),
                        tight.to_degrees()
                    ));
                }
            }
        }
        for seg in &self.segments {
            let (SegmentKind::Arc(kind), Scaling::Arc { pulley, start, end }) = (seg.kind, seg.scaling) else { continue };
            let wrap = p[start] - p[end];
            if !(wrap >= -slack) {
                let name = pulley.name();
                return Err(match kind {
                    ArcKind::Frictionless => format!("non-positive wrap {:.3}° on the {name} pulley", wrap.to_degrees()),
                    ArcKind::Stick => format!(
                        "the stick arc on the {name} pulley would be negative ({wrap:.4e} rad): the slip zone covers the whole contact arc"
                    ),
                    ArcKind::Slip => {
                        format!("the slip arc on the {name} pulley would be negative ({wrap:.4e} rad): the slip direction reverses")
                    }
                });
            }
        }
        for seg in &self.segments {
            if let Scaling::Span { param } = seg.scaling {
                if !(p[param] > 0.0) {
                    return Err(format!("a span half has non-positive length {:.3e}", p[param]));
                }
            }
        }
        if let Some(m) = self.motion {
            if !(self.direction.sign() * p[m.transport] >= -1e-12) {
                let sense = match self.direction {
                    Direction::Clockwise => "negative",
                    Direction::CounterClockwise => "positive",
                };
                return Err(format!("{sense} transport rate {:.3e} against the running direction", p[m.transport]));
            }
        }
        Ok(())
    }

    /// Parameters of the tight loop (straight spans of parameter `span`, half-turn arcs;
    /// with friction all stick, slip arcs of zero length), the topology part of an
    /// exact start; the jump and the motion are 0.
    pub fn tight_params(&self, span: f64) -> Vec<f64> {
        let mut p = vec![0.0; self.n_params()];
        for seg in &self.segments {
            if let Scaling::Span { param } = seg.scaling {
                p[param] = span;
            }
        }
        for pulley in self.pulleys() {
            let (a, b) = pulley.tight_angles();
            let arcs = self.arcs_on(pulley);
            for (i, &k) in arcs.iter().enumerate() {
                let Scaling::Arc { start, end, .. } = self.segments[k].scaling else { unreachable!("an arc") };
                if i == 0 {
                    p[start] = a;
                }
                // a slip arc before the stick arc (counter-clockwise) has zero length too
                let zero_slip_before = i + 1 < arcs.len() && self.segments[k].kind == SegmentKind::Arc(ArcKind::Slip);
                p[end] = if zero_slip_before { a } else { b };
            }
        }
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The frictionless loop: the six segments and nine parameters of
    /// docs/string-hanging.md, in its order and with its names.
    #[test]
    fn frictionless_loop_is_the_six_segment_layout() {
        let t = Topology::two_pulley(ContactModel::Frictionless);
        assert_eq!(t.len(), 6);
        assert_eq!(t.param_names(), ["l0", "l1", "l3", "l4", "phi2a", "phi2b", "phi1a", "phi1b", "defect"]);
        assert_eq!(t.closure_jump(), Some(8));
        assert_eq!(t.motion(), None);
        assert!(!t.has_friction());
        let spans: Vec<usize> = (0..6).filter(|&k| t.is_span(k)).collect();
        assert_eq!(spans, [0, 1, 3, 4]);
        assert_eq!(t.sides(), [Side::UpperSpan, Side::UpperSpan, Side::Arc, Side::LowerSpan, Side::LowerSpan, Side::Arc]);
        assert_eq!(t.segment(2).scaling, Scaling::Arc { pulley: Pulley::Driven, start: 4, end: 5 });
        assert_eq!(t.segment(5).scaling, Scaling::Arc { pulley: Pulley::Driver, start: 6, end: 7 });
        assert_eq!(t.segment(3).scaling, Scaling::Span { param: 2 });
        assert_eq!(t.junction(0), Junction::MidSpan);
        assert_eq!(t.junction(1), Junction::ContactStart { pulley: Pulley::Driven, angle: 4 });
        assert_eq!(t.junction(2), Junction::ContactEnd { pulley: Pulley::Driven, angle: 5, closes_loop: false });
        assert_eq!(t.junction(5), Junction::ContactEnd { pulley: Pulley::Driver, angle: 7, closes_loop: true });
        assert_eq!(t.mid_spans(), (0, 3));
        assert_eq!(t.spans_around(Pulley::Driver), (4, 0));
        assert_eq!(t.spans_around(Pulley::Driven), (1, 3));
        assert_eq!(t.transition_angle(Pulley::Driver), None);
    }

    /// With friction: each arc splits into stick then slip, sharing the angle φ_t; the
    /// twelve parameters of docs/string-drive.md.
    #[test]
    fn coulomb_loop_has_stick_then_slip() {
        let t = Topology::two_pulley(ContactModel::Coulomb);
        assert_eq!(t.len(), 8);
        assert_eq!(
            t.param_names(),
            ["l0", "l1", "l4", "l5", "phi2a", "phi2t", "phi2b", "phi1a", "phi1t", "phi1b", "c", "omega2"]
        );
        assert_eq!(t.motion(), Some(Motion { transport: 10, driven_speed: 11 }));
        assert_eq!(t.closure_jump(), None);
        assert!(t.has_friction());
        assert_eq!(t.segment(2).kind, SegmentKind::Arc(ArcKind::Stick));
        assert_eq!(t.segment(3).kind, SegmentKind::Arc(ArcKind::Slip));
        assert_eq!(t.segment(2).scaling, Scaling::Arc { pulley: Pulley::Driven, start: 4, end: 5 });
        assert_eq!(t.segment(3).scaling, Scaling::Arc { pulley: Pulley::Driven, start: 5, end: 6 });
        assert_eq!(t.junction(2), Junction::ArcToArc { pulley: Pulley::Driven, angle: 5 });
        assert_eq!(t.junction(7), Junction::ContactEnd { pulley: Pulley::Driver, angle: 9, closes_loop: true });
        assert_eq!(t.arc(Pulley::Driver, ArcKind::Stick), Some(6));
        assert_eq!(t.arc(Pulley::Driver, ArcKind::Frictionless), None);
        assert_eq!((t.transition_angle(Pulley::Driver), t.transition_angle(Pulley::Driven)), (Some(8), Some(5)));
        assert_eq!((t.first_arc(Pulley::Driver), t.last_arc(Pulley::Driver)), (6, 7));
        assert_eq!(t.mid_spans(), (0, 4));
        let p = t.tight_params(0.4);
        assert_eq!(t.contact_angles(Pulley::Driven, &p), [FRAC_PI_2, -FRAC_PI_2, -FRAC_PI_2]);
        assert_eq!(t.contact_angles(Pulley::Driver, &p), [-FRAC_PI_2, -1.5 * PI, -1.5 * PI]);
        assert_eq!(&p[..4], [0.4; 4]);
        assert_eq!(&p[10..], [0.0; 2]);
    }

    /// Counter-clockwise the belt runs onto each pulley at its last contact along σ: slip
    /// then stick, the same angles and parameters; the transport rate must be ≤ 0 and the
    /// slip signs follow the direction and the power flow.
    #[test]
    fn counter_clockwise_loop_has_slip_then_stick() {
        let cw = Topology::two_pulley(ContactModel::Coulomb);
        let t = Topology::two_pulley_running(ContactModel::Coulomb, Direction::CounterClockwise);
        assert_eq!(t.direction(), Direction::CounterClockwise);
        assert_eq!(t.param_names(), cw.param_names());
        assert_eq!(t.segment(2).kind, SegmentKind::Arc(ArcKind::Slip));
        assert_eq!(t.segment(3).kind, SegmentKind::Arc(ArcKind::Stick));
        assert_eq!(t.segment(6).kind, SegmentKind::Arc(ArcKind::Slip));
        assert_eq!(t.segment(7).kind, SegmentKind::Arc(ArcKind::Stick));
        assert_eq!(t.segment(2).scaling, Scaling::Arc { pulley: Pulley::Driven, start: 4, end: 5 });
        assert_eq!(t.segment(3).scaling, Scaling::Arc { pulley: Pulley::Driven, start: 5, end: 6 });
        assert_eq!(t.arc(Pulley::Driver, ArcKind::Stick), Some(7));
        assert_eq!((t.transition_angle(Pulley::Driver), t.transition_angle(Pulley::Driven)), (Some(8), Some(5)));
        let mut p = t.tight_params(0.4);
        assert_eq!(t.contact_angles(Pulley::Driven, &p), [FRAC_PI_2, FRAC_PI_2, -FRAC_PI_2]);
        assert_eq!(t.check(&p, FRAC_PI_2, 1e-9), Ok(()));
        p[10] = -0.3;
        assert_eq!(t.check(&p, FRAC_PI_2, 1e-9), Ok(()));
        assert!(cw.check(&p, FRAC_PI_2, 1e-9).unwrap_err().contains("negative transport rate"));
        p[10] = 1e-6;
        assert!(t.check(&p, FRAC_PI_2, 1e-9).unwrap_err().contains("positive transport rate"));
        let (cw, ccw) = (Direction::Clockwise, Direction::CounterClockwise);
        for (dir, flow, driver) in [
            (cw, PowerFlow::FromDriver, 1.0),
            (cw, PowerFlow::FromDriven, -1.0),
            (ccw, PowerFlow::FromDriver, -1.0),
            (ccw, PowerFlow::FromDriven, 1.0),
        ] {
            assert_eq!(Pulley::Driver.slip_sign(dir, flow), driver);
            assert_eq!(Pulley::Driven.slip_sign(dir, flow), -driver);
        }
        assert_eq!(PowerFlow::of_load(2.0, cw), PowerFlow::FromDriver);
        assert_eq!(PowerFlow::of_load(-2.0, cw), PowerFlow::FromDriven);
        assert_eq!(PowerFlow::of_load(-2.0, ccw), PowerFlow::FromDriver);
        assert_eq!(PowerFlow::of_load(2.0, ccw), PowerFlow::FromDriven);
        assert_eq!(PowerFlow::of_load(0.0, ccw), PowerFlow::FromDriver);
    }

    /// The open one-pulley layout: four segments on the single pulley, five parameters,
    /// the contact junctions of the loop and `OpenEnds` after the outflow span; the
    /// acceptance check sees the one pulley only.
    #[test]
    fn one_pulley_is_open() {
        let t = Topology::one_pulley();
        assert!(t.is_open() && t.has_friction() && t.motion().is_none() && t.closure_jump().is_none());
        assert_eq!(t.param_names(), ["l0", "l3", "phi_a", "phi_t", "phi_b"]);
        assert_eq!(t.pulleys(), [Pulley::Single]);
        assert_eq!(t.junction(0), Junction::ContactStart { pulley: Pulley::Single, angle: 2 });
        assert_eq!(t.junction(1), Junction::ArcToArc { pulley: Pulley::Single, angle: 3 });
        assert_eq!(t.junction(2), Junction::ContactEnd { pulley: Pulley::Single, angle: 4, closes_loop: false });
        assert_eq!(t.junction(3), Junction::OpenEnds);
        assert_eq!(t.sides(), [Side::UpperSpan, Side::Arc, Side::Arc, Side::LowerSpan]);
        let p = t.tight_params(3.0);
        assert_eq!(p, [3.0, 3.0, FRAC_PI_2, -FRAC_PI_2, -FRAC_PI_2]);
        assert_eq!(t.check(&p, FRAC_PI_2, 1e-9), Ok(()));
        let mut q = p.clone();
        q[3] = FRAC_PI_2 + 0.1;
        assert!(t.check(&q, FRAC_PI_2, 1e-9).unwrap_err().contains("stick arc on the pulley pulley"));
        assert!(!Topology::two_pulley(ContactModel::Coulomb).is_open());
        assert_eq!(Topology::two_pulley(ContactModel::Coulomb).pulleys(), [Pulley::Driven, Pulley::Driver]);
    }

    /// The scene decides the topology by its contact effect.
    #[test]
    fn built_from_the_scene_contact() {
        let scene = |name: &str| {
            let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes").join(name);
            drive::scene::Scene::from_path(&path).expect("catalogue scene")
        };
        let hanging = scene("string-hanging.json");
        assert_eq!(Topology::from_scene(&hanging), Ok(Topology::two_pulley(ContactModel::Frictionless)));
        let drive = scene("string-drive.json");
        assert_eq!(Topology::from_scene(&drive), Ok(Topology::two_pulley(ContactModel::Coulomb)));
    }

    /// The acceptance test: the tight loop passes; each violation is named.
    #[test]
    fn check_names_each_violation() {
        let t = Topology::two_pulley(ContactModel::Coulomb);
        let p = t.tight_params(0.4);
        assert_eq!(t.check(&p, FRAC_PI_2, 1e-9), Ok(()));
        let mut q = p.clone();
        q[5] = FRAC_PI_2 + 0.1; // φ_t above φ_a on the driven pulley
        assert!(t.check(&q, FRAC_PI_2, 1e-9).unwrap_err().contains("stick arc on the driven pulley"));
        let mut q = p.clone();
        q[8] = -1.5 * PI - 0.1; // φ_t below φ_b on the driver
        assert!(t.check(&q, FRAC_PI_2, 1e-9).unwrap_err().contains("slip arc on the driver pulley"));
        let mut q = p.clone();
        q[7] = 0.2 + 0.5 * PI; // first contact on the driver a half turn off
        assert!(t.check(&q, FRAC_PI_2, 1e-9).unwrap_err().contains("first contact on the driver pulley"));
        let mut q = p.clone();
        q[2] = -0.1;
        assert!(t.check(&q, FRAC_PI_2, 1e-9).unwrap_err().contains("non-positive length"));
        let mut q = p;
        q[10] = -1e-6;
        assert!(t.check(&q, FRAC_PI_2, 1e-9).unwrap_err().contains("transport rate"));
        let f = Topology::two_pulley(ContactModel::Frictionless);
        let mut q = f.tight_params(0.4);
        (q[4], q[5]) = (0.0, 0.1); // within a half turn of (π/2, −π/2), but a negative wrap
        assert!(f.check(&q, PI, 0.0).unwrap_err().contains("non-positive wrap"));
        assert!(f.check(&q, FRAC_PI_2, 0.0).unwrap_err().contains("first contact on the driven pulley"));
        q[4] = f64::NAN;
        assert!(f.check(&q, PI, 0.0).is_err());
    }
}
