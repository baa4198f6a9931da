//! The named scalars of a solution (`summary` of DESIGN.md's result format).
//!
//! A quantity that a scene's effects do not produce is `None` and is *absent* from
//! the JSON (never `0`, never `null`). Quantities are typed ids ([`Quantity`]: a
//! [`Global`] quantity, or a [`PulleyQuantity`] of a [`PulleyId`]); their flat names
//! ([`SCALAR_NAMES`]: `y_upper_mid`, `driver.contact_arc`, ...) are what the JSON, the
//! gate blocks and the harness's tables use.
//!
//! Sign and unit conventions (DESIGN.md "Result format"):
//! - `*_mid`: at x = 0 on the upper / lower span;
//! - `tension_*`: axial force N (not the effective tension T − ρc²λ), N;
//! - `moment_*`: bending moment, N·m;
//! - arcs in rad; `contact_start`/`contact_end`: polar angle atan2(y − y_c, x − x_c)
//!   ∈ (−π, π] of the first/last contact point in the direction of σ;
//! - `torque`: moment about the pulley axis exerted by the belt on the pulley, N·m,
//!   clockwise positive (the driving sense);
//! - `edge_force_*`: concentrated normal reaction at a contact boundary (unshearable
//!   rods), N;
//! - `edge_pressure_*`: contact pressure per unit reference length just inside the
//!   zone at its first/last point (Cosserat rods: finite, no edge forces), N/m;
//! - `tension_tight`/`tension_slack`: the axial force in the driver's / the driven
//!   pulley's stick zone in steady motion, at the middle of the stick arc, N;
//! - one-pulley scenes (open ends, Paper C): the pulley as `pulley.*`, and
//!   `pulley_speed` (ω, rad/s, clockwise positive), `tension_in`/`tension_out` (axial
//!   force at the inflow/outflow end, N), `y_in`/`y_out` (y of the centreline at the
//!   end sections, m);
//! - `driven_speed`: ω₂, rad/s, clockwise positive;
//! - `transport_rate`: c = mass flux / ρ, m/s (unstretched length per unit time).

use serde::{Deserialize, Serialize};

use crate::error::ResultError;
use crate::suggest::nearest;

/// A quantity of the whole belt (top level of `summary`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Global {
    /// y at x = 0 on the upper span, m.
    YUpperMid,
    /// y at x = 0 on the lower span, m.
    YLowerMid,
    /// Axial force at x = 0 on the upper span, N.
    TensionUpperMid,
    /// Axial force at x = 0 on the lower span, N.
    TensionLowerMid,
    /// Bending moment at x = 0 on the upper span, N·m.
    MomentUpperMid,
    /// Bending moment at x = 0 on the lower span, N·m.
    MomentLowerMid,
    /// Axial force in the driver's stick zone (middle of the stick arc), N.
    TensionTight,
    /// Axial force in the driven pulley's stick zone (middle of the stick arc), N.
    TensionSlack,
    /// ω₂, rad/s.
    DrivenSpeed,
    /// c = mass flux / ρ, m/s.
    TransportRate,
    /// ω of the single pulley of a one-pulley scene, rad/s.
    PulleySpeed,
    /// Axial force at the inflow end of a one-pulley scene, N.
    TensionIn,
    /// Axial force at the outflow end of a one-pulley scene, N.
    TensionOut,
    /// y of the centreline at the inflow end section, m.
    YIn,
    /// y of the centreline at the outflow end section, m.
    YOut,
    /// Lateral run-off velocity of the shell belt, m/s (+z: along the drum axes).
    RunoffVelocity,
    /// The shell's run-off velocity after its lateral transient (a damped-oscillation fit).
    SettledRunoffVelocity,
    /// Lateral drift of the shell belt per belt revolution, m.
    DriftPerRevolution,
    /// Largest membrane stress at the belt edges, Pa.
    EdgeStressMax,
}

/// Which pulley a [`PulleyQuantity`] belongs to: `driver`/`driven` of the two-pulley
/// loop, or the single `pulley` of a one-pulley scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PulleyId {
    /// The left pulley of the loop, at (−H/2, 0).
    Driver,
    /// The right pulley of the loop, at (+H/2, 0).
    Driven,
    /// The pulley of a one-pulley scene, at the origin.
    Pulley,
}

/// A contact quantity of one pulley (`summary.<pulley>.<quantity>`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PulleyQuantity {
    /// Angle of the contact zone, rad.
    ContactArc,
    /// Polar angle of the first contact point in the direction of travel, rad.
    ContactStart,
    /// Polar angle of the last contact point in the direction of travel, rad.
    ContactEnd,
    /// Angle of the stick zone, rad.
    StickArc,
    /// Angle of the slip zone, rad.
    SlipArc,
    /// Torque of the belt on the pulley, N·m, clockwise positive.
    Torque,
    /// Concentrated normal reaction at the first contact point, N.
    EdgeForceStart,
    /// Concentrated normal reaction at the last contact point, N.
    EdgeForceEnd,
    /// Contact pressure just inside the zone at its first point, N/m.
    EdgePressureStart,
    /// Contact pressure just inside the zone at its last point, N/m.
    EdgePressureEnd,
    /// Smallest contact pressure over the contact zone, N/m (Cosserat rods).
    PressureMin,
    /// Polar angle of the stick → slip point, rad (Coulomb friction in steady motion).
    StickSlipAngle,
    /// Largest |shear strain Γ₂| over the contact zone (Cosserat rods).
    ShearStrainMax,
    /// Bending moment at the first contact point, N·m (Cosserat rods).
    MomentStart,
    /// Bending moment at the last contact point, N·m (Cosserat rods).
    MomentEnd,
    /// Stretch λ of the stick zone (Coulomb friction in steady motion).
    StretchStick,
    /// Power dissipated by slip on the pulley, W (Coulomb friction in steady motion).
    Dissipation,
}

/// A summary quantity: the typed id behind each flat name of [`SCALAR_NAMES`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Quantity {
    /// A quantity of the whole belt.
    Global(Global),
    /// A contact quantity of one pulley.
    Pulley(PulleyId, PulleyQuantity),
}

impl Global {
    /// Every global quantity, in the order of the result format.
    pub const ALL: [Global; 19] = [
        Global::YUpperMid,
        Global::YLowerMid,
        Global::TensionUpperMid,
        Global::TensionLowerMid,
        Global::MomentUpperMid,
        Global::MomentLowerMid,
        Global::TensionTight,
        Global::TensionSlack,
        Global::DrivenSpeed,
        Global::TransportRate,
        Global::PulleySpeed,
        Global::TensionIn,
        Global::TensionOut,
        Global::YIn,
        Global::YOut,
        Global::RunoffVelocity,
        Global::SettledRunoffVelocity,
        Global::DriftPerRevolution,
        Global::EdgeStressMax,
    ];

    /// The JSON name.
    pub const fn name(self) -> &'static str {
        match self {
            Global::YUpperMid => "y_upper_mid",
            Global::YLowerMid => "y_lower_mid",
            Global::TensionUpperMid => "tension_upper_mid",
            Global::TensionLowerMid => "tension_lower_mid",
            Global::MomentUpperMid => "moment_upper_mid",
            Global::MomentLowerMid => "moment_lower_mid",
            Global::TensionTight => "tension_tight",
            Global::TensionSlack => "tension_slack",
            Global::DrivenSpeed => "driven_speed",
            Global::TransportRate => "transport_rate",
            Global::PulleySpeed => "pulley_speed",
            Global::TensionIn => "tension_in",
            Global::TensionOut => "tension_out",
            Global::YIn => "y_in",
            Global::YOut => "y_out",
            Global::RunoffVelocity => "runoff_velocity",
            Global::SettledRunoffVelocity => "settled_runoff_velocity",
            Global::DriftPerRevolution => "drift_per_revolution",
            Global::EdgeStressMax => "edge_stress_max",
        }
    }
    /// The unit of the quantity (SI).
    pub const fn unit(self) -> &'static str {
        match self {
            Global::YUpperMid | Global::YLowerMid | Global::YIn | Global::YOut => "m",
            Global::TensionUpperMid
            | Global::TensionLowerMid
            | Global::TensionTight
            | Global::TensionSlack
            | Global::TensionIn
            | Global::TensionOut => "N",
            Global::MomentUpperMid | Global::MomentLowerMid => "N·m",
            Global::DrivenSpeed | Global::PulleySpeed => "rad/s",
            Global::TransportRate | Global::RunoffVelocity | Global::SettledRunoffVelocity => "m/s",
            Global::DriftPerRevolution => "m",
            Global::EdgeStressMax => "Pa",
        }
    }

    /// What the quantity is, in one line (the `beltcheck quantities` table and the
    /// help text print it).
    pub const fn meaning(self) -> &'static str {
        match self {
            Global::YUpperMid => "y of the centreline at x = 0 on the upper span",
            Global::YLowerMid => "y of the centreline at x = 0 on the lower span",
            Global::TensionUpperMid => "axial force at x = 0 on the upper span (not the effective tension)",
            Global::TensionLowerMid => "axial force at x = 0 on the lower span (not the effective tension)",
            Global::MomentUpperMid => "bending moment at x = 0 on the upper span",
            Global::MomentLowerMid => "bending moment at x = 0 on the lower span",
            Global::TensionTight => {
                "axial force in the driver's stick zone in steady motion, at the middle of the stick arc: the tight side while the driver drives (either sense of rotation), the slack side when the load drives"
            }
            Global::TensionSlack => {
                "axial force in the driven pulley's stick zone in steady motion, at the middle of the stick arc: the slack side while the driver drives, the tight side when the load drives"
            }
            Global::DrivenSpeed => "angular speed ω₂ of the driven pulley, clockwise positive",
            Global::TransportRate => "transport rate c = mass flux / ρ (unstretched length per unit time), positive along σ (clockwise), negative for a counter-clockwise driver",
            Global::PulleySpeed => "angular speed ω of the single pulley of a one-pulley scene, clockwise positive",
            Global::TensionIn => "axial force at the inflow end of a one-pulley scene",
            Global::TensionOut => "axial force at the outflow end of a one-pulley scene",
            Global::YIn => "y of the centreline at the inflow end section of a one-pulley scene",
            Global::YOut => "y of the centreline at the outflow end section of a one-pulley scene",
            Global::RunoffVelocity => {
                "lateral run-off velocity of a shell belt (+z along the drum axes): least-squares slope of its mean lateral offset over the last whole belt revolution of the rotation (over the whole rotation if shorter)"
            }
            Global::SettledRunoffVelocity => {
                "lateral run-off velocity of a shell belt after its lateral transient: the drift of a fit of a line under a damped oscillation to its mean lateral offset over the last third of the rotation after the steering's last change, confirmed by the fit over the last half (absent, with a warning, when the transient has not settled)"
            }
            Global::DriftPerRevolution => "lateral drift of a shell belt per belt revolution L/(ω₁R): runoff_velocity × L/(ω₁R)",
            Global::EdgeStressMax => "largest |membrane stress along the belt| n_σσ/h at the two belt edges ζ = ±b/2 at the end of a shell run",
        }
    }
}

impl PulleyId {
    /// Every pulley, in the order of the result format.
    pub const ALL: [PulleyId; 3] = [PulleyId::Driver, PulleyId::Driven, PulleyId::Pulley];

    /// The JSON name of the pulley block.
    pub const fn name(self) -> &'static str {
        match self {
            PulleyId::Driver => "driver",
            PulleyId::Driven => "driven",
            PulleyId::Pulley => "pulley",
        }
    }
}

impl PulleyQuantity {
    /// Every pulley quantity, in the order of the result format.
    pub const ALL: [PulleyQuantity; 17] = [
        PulleyQuantity::ContactArc,
        PulleyQuantity::ContactStart,
        PulleyQuantity::ContactEnd,
        PulleyQuantity::StickArc,
        PulleyQuantity::SlipArc,
        PulleyQuantity::Torque,
        PulleyQuantity::EdgeForceStart,
        PulleyQuantity::EdgeForceEnd,
        PulleyQuantity::EdgePressureStart,
        PulleyQuantity::EdgePressureEnd,
        PulleyQuantity::PressureMin,
        PulleyQuantity::StickSlipAngle,
        PulleyQuantity::ShearStrainMax,
        PulleyQuantity::MomentStart,
        PulleyQuantity::MomentEnd,
        PulleyQuantity::StretchStick,
        PulleyQuantity::Dissipation,
    ];

    /// The JSON name inside a pulley block.
    pub const fn name(self) -> &'static str {
        match self {
            PulleyQuantity::ContactArc => "contact_arc",
            PulleyQuantity::ContactStart => "contact_start",
            PulleyQuantity::ContactEnd => "contact_end",
            PulleyQuantity::StickArc => "stick_arc",
            PulleyQuantity::SlipArc => "slip_arc",
            PulleyQuantity::Torque => "torque",
            PulleyQuantity::EdgeForceStart => "edge_force_start",
            PulleyQuantity::EdgeForceEnd => "edge_force_end",
            PulleyQuantity::EdgePressureStart => "edge_pressure_start",
            PulleyQuantity::EdgePressureEnd => "edge_pressure_end",
            PulleyQuantity::PressureMin => "pressure_min",
            PulleyQuantity::StickSlipAngle => "stick_slip_angle",
            PulleyQuantity::ShearStrainMax => "shear_strain_max",
            PulleyQuantity::MomentStart => "moment_start",
            PulleyQuantity::MomentEnd => "moment_end",
            PulleyQuantity::StretchStick => "stretch_stick",
            PulleyQuantity::Dissipation => "dissipation",
        }
    }
}

impl PulleyQuantity {
    /// The unit of the quantity (SI; angles in rad).
    pub const fn unit(self) -> &'static str {
        match self {
            PulleyQuantity::ContactArc
            | PulleyQuantity::ContactStart
            | PulleyQuantity::ContactEnd
            | PulleyQuantity::StickArc
            | PulleyQuantity::SlipArc
            | PulleyQuantity::StickSlipAngle => "rad",
            PulleyQuantity::Torque => "N·m",
            PulleyQuantity::EdgeForceStart | PulleyQuantity::EdgeForceEnd => "N",
            PulleyQuantity::EdgePressureStart | PulleyQuantity::EdgePressureEnd | PulleyQuantity::PressureMin => "N/m",
            PulleyQuantity::ShearStrainMax | PulleyQuantity::StretchStick => "1",
            PulleyQuantity::MomentStart | PulleyQuantity::MomentEnd => "N·m",
            PulleyQuantity::Dissipation => "W",
        }
    }

    /// What the quantity is, in one line.
    pub const fn meaning(self) -> &'static str {
        match self {
            PulleyQuantity::ContactArc => "angle of the contact zone",
            PulleyQuantity::ContactStart => {
                "polar angle atan2(y − y_c, x − x_c) ∈ (−π, π] of the first contact point in the direction of σ"
            }
            PulleyQuantity::ContactEnd => {
                "polar angle atan2(y − y_c, x − x_c) ∈ (−π, π] of the last contact point in the direction of σ"
            }
            PulleyQuantity::StickArc => "angle of the stick zone (friction drives)",
            PulleyQuantity::SlipArc => "angle of the slip zone (friction drives)",
            PulleyQuantity::Torque => "moment of the belt on the pulley about its axis, clockwise positive",
            PulleyQuantity::EdgeForceStart => {
                "concentrated normal reaction at the first contact point (unshearable rods)"
            }
            PulleyQuantity::EdgeForceEnd => "concentrated normal reaction at the last contact point (unshearable rods)",
            PulleyQuantity::EdgePressureStart => {
                "contact pressure per unit reference length just inside the zone at its first point (Cosserat rods)"
            }
            PulleyQuantity::EdgePressureEnd => {
                "contact pressure per unit reference length just inside the zone at its last point (Cosserat rods)"
            }
            PulleyQuantity::PressureMin => {
                "smallest contact pressure per unit reference length over the contact zone, its edges included (Cosserat rods; admissibility needs it > 0)"
            }
            PulleyQuantity::StickSlipAngle => {
                "polar angle atan2(y − y_c, x − x_c) ∈ (−π, π] of the stick → slip point (friction drives in steady motion with a slip zone)"
            }
            PulleyQuantity::ShearStrainMax => "largest |shear strain Γ₂| over the contact zone, its edges included (Cosserat rods)",
            PulleyQuantity::MomentStart => "bending moment at the first contact point in the direction of σ (Cosserat rods)",
            PulleyQuantity::MomentEnd => "bending moment at the last contact point in the direction of σ (Cosserat rods)",
            PulleyQuantity::StretchStick => {
                "stretch λ of the stick zone, at the middle of the stick arc (friction drives in steady motion; the pulley's surface speed is c λ)"
            }
            PulleyQuantity::Dissipation => {
                "power dissipated by slip on the pulley, ∫_slip f_t (ωR − cλ) ds ≥ 0 (friction drives in steady motion)"
            }
        }
    }
}

/// Number of summary quantities: the globals, then each pulley's quantities.
const N_QUANTITIES: usize = Global::ALL.len() + PulleyId::ALL.len() * PulleyQuantity::ALL.len();

/// The flat names of every quantity, in [`Quantity::ALL`]'s order, as a table
/// (the pulley names cannot be concatenated in a const context).
const TABLE: [&str; N_QUANTITIES] = [
    "y_upper_mid", "y_lower_mid", "tension_upper_mid", "tension_lower_mid", "moment_upper_mid",
    "moment_lower_mid", "tension_tight", "tension_slack", "driven_speed", "transport_rate",
    "pulley_speed", "tension_in", "tension_out", "y_in", "y_out",
    "runoff_velocity", "settled_runoff_velocity", "drift_per_revolution", "edge_stress_max",
    "driver.contact_arc", "driver.contact_start", "driver.contact_end", "driver.stick_arc",
    "driver.slip_arc", "driver.torque", "driver.edge_force_start", "driver.edge_force_end",
    "driver.edge_pressure_start", "driver.edge_pressure_end",
    "driver.pressure_min", "driver.stick_slip_angle", "driver.shear_strain_max", "driver.moment_start",
    "driver.moment_end", "driver.stretch_stick", "driver.dissipation",
    "driven.contact_arc", "driven.contact_start", "driven.contact_end", "driven.stick_arc",
    "driven.slip_arc", "driven.torque", "driven.edge_force_start", "driven.edge_force_end",
    "driven.edge_pressure_start", "driven.edge_pressure_end",
    "driven.pressure_min", "driven.stick_slip_angle", "driven.shear_strain_max", "driven.moment_start",
    "driven.moment_end", "driven.stretch_stick", "driven.dissipation",
    "pulley.contact_arc", "pulley.contact_start", "pulley.contact_end", "pulley.stick_arc",
    "pulley.slip_arc", "pulley.torque", "pulley.edge_force_start", "pulley.edge_force_end",
    "pulley.edge_pressure_start", "pulley.edge_pressure_end",
    "pulley.pressure_min", "pulley.stick_slip_angle", "pulley.shear_strain_max", "pulley.moment_start",
    "pulley.moment_end", "pulley.stretch_stick", "pulley.dissipation",
];

/// Every flat name [`Summary::scalars`] can produce, in its order (a unit test holds
/// it equal to the names of [`Quantity::ALL`]).
pub const SCALAR_NAMES: [&str; N_QUANTITIES] = TABLE;

impl Quantity {
    /// Every quantity, in the order of the result format: globals, then `driver.*`,
    /// `driven.*`, `pulley.*`.
    pub const ALL: [Quantity; N_QUANTITIES] = {
        let mut all = [Quantity::Global(Global::YUpperMid); N_QUANTITIES];
        let mut k = 0;
        while k < Global::ALL.len() {
            all[k] = Quantity::Global(Global::ALL[k]);
            k += 1;
        }
        let mut p = 0;
        while p < PulleyId::ALL.len() {
            let mut q = 0;
            while q < PulleyQuantity::ALL.len() {
                all[k] = Quantity::Pulley(PulleyId::ALL[p], PulleyQuantity::ALL[q]);
                k += 1;
                q += 1;
            }
            p += 1;
        }
        all
    };

    /// Position in [`Quantity::ALL`] and [`SCALAR_NAMES`].
    pub const fn index(self) -> usize {
        match self {
            Quantity::Global(g) => g as usize,
            Quantity::Pulley(p, q) => Global::ALL.len() + p as usize * PulleyQuantity::ALL.len() + q as usize,
        }
    }

    /// The unit (SI; angles in rad).
    pub const fn unit(self) -> &'static str {
        match self {
            Quantity::Global(g) => g.unit(),
            Quantity::Pulley(_, q) => q.unit(),
        }
    }

    /// What the quantity is, in one line (for a pulley quantity: of that pulley).
    pub const fn meaning(self) -> &'static str {
        match self {
            Quantity::Global(g) => g.meaning(),
            Quantity::Pulley(_, q) => q.meaning(),
        }
    }

    /// The flat name, e.g. `y_upper_mid` or `driver.contact_arc`.
    pub const fn name(self) -> &'static str {
        TABLE[self.index()]
    }

    /// The quantity of a flat name.
    ///
    /// # Errors
    /// [`ResultError::UnknownQuantity`] with the nearest valid name.
    pub fn parse(name: &str) -> Result<Quantity, ResultError> {
        match TABLE.iter().position(|n| *n == name) {
            Some(k) => Ok(Quantity::ALL[k]),
            None => Err(ResultError::UnknownQuantity { name: name.to_string(), suggestion: nearest(name, TABLE.iter().copied()) }),
        }
    }
}

impl std::fmt::Display for Quantity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The value getter and the slot of an enum of quantities, from one list of
/// `Variant => field` pairs (so the two cannot disagree).
macro_rules! accessors {
    ($kind:ident: $get:ident, $slot:ident; $($variant:ident => $field:ident),+ $(,)?) => {
        /// The value of one quantity.
        pub fn $get(&self, q: $kind) -> Option<f64> {
            match q {
                $($kind::$variant => self.$field,)+
            }
        }

        /// The slot of one quantity.
        pub fn $slot(&mut self, q: $kind) -> &mut Option<f64> {
            match q {
                $($kind::$variant => &mut self.$field,)+
            }
        }
    };
}

/// Contact quantities of one pulley (`summary.driver`, `summary.driven`,
/// `summary.pulley`); see [`PulleyQuantity`] for each field.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct PulleySummary {
    /// Angle of the contact zone, rad.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_arc: Option<f64>,
    /// Polar angle of the first contact point in the direction of σ, rad, (−π, π].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_start: Option<f64>,
    /// Polar angle of the last contact point in the direction of σ, rad, (−π, π].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_end: Option<f64>,
    /// Angle of the stick zone, rad (Coulomb friction only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stick_arc: Option<f64>,
    /// Angle of the slip zone, rad (Coulomb friction only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slip_arc: Option<f64>,
    /// Torque of the belt on the pulley, N·m, clockwise positive.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torque: Option<f64>,
    /// Concentrated normal reaction at the first contact point, N (unshearable rods).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edge_force_start: Option<f64>,
    /// Concentrated normal reaction at the last contact point, N (unshearable rods).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edge_force_end: Option<f64>,
    /// Contact pressure just inside the zone at its first point, N/m (Cosserat rods).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edge_pressure_start: Option<f64>,
    /// Contact pressure just inside the zone at its last point, N/m (Cosserat rods).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edge_pressure_end: Option<f64>,
    /// Smallest contact pressure over the contact zone, N/m (Cosserat rods).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure_min: Option<f64>,
    /// Polar angle of the stick → slip point, rad, (−π, π] (friction drives).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stick_slip_angle: Option<f64>,
    /// Largest |shear strain Γ₂| over the contact zone (Cosserat rods).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shear_strain_max: Option<f64>,
    /// Bending moment at the first contact point, N·m (Cosserat rods).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub moment_start: Option<f64>,
    /// Bending moment at the last contact point, N·m (Cosserat rods).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub moment_end: Option<f64>,
    /// Stretch λ of the stick zone (friction drives).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stretch_stick: Option<f64>,
    /// Power dissipated by slip on the pulley, W (friction drives).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dissipation: Option<f64>,
}

impl PulleySummary {
    /// The field names, in the order of the result format.
    pub const NAMES: [&'static str; 17] = {
        let mut names = [""; 17];
        let mut q = 0;
        while q < 17 {
            names[q] = PulleyQuantity::ALL[q].name();
            q += 1;
        }
        names
    };

    accessors!(PulleyQuantity: get, slot_mut;
        ContactArc => contact_arc, ContactStart => contact_start, ContactEnd => contact_end,
        StickArc => stick_arc, SlipArc => slip_arc, Torque => torque,
        EdgeForceStart => edge_force_start, EdgeForceEnd => edge_force_end,
        EdgePressureStart => edge_pressure_start, EdgePressureEnd => edge_pressure_end,
        PressureMin => pressure_min, StickSlipAngle => stick_slip_angle, ShearStrainMax => shear_strain_max,
        MomentStart => moment_start, MomentEnd => moment_end, StretchStick => stretch_stick, Dissipation => dissipation);
}

/// Named scalars of one solution; see the module docs for units and signs, and
/// [`Global`] for each top-level field.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Summary {
    /// y at x = 0 on the upper span, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y_upper_mid: Option<f64>,
    /// y at x = 0 on the lower span, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y_lower_mid: Option<f64>,
    /// Axial force at x = 0 on the upper span, N.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tension_upper_mid: Option<f64>,
    /// Axial force at x = 0 on the lower span, N.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tension_lower_mid: Option<f64>,
    /// Bending moment at x = 0 on the upper span, N·m (rods and shells).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub moment_upper_mid: Option<f64>,
    /// Bending moment at x = 0 on the lower span, N·m (rods and shells).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub moment_lower_mid: Option<f64>,
    /// Axial force in the driver's stick zone in steady motion, at the middle of the
    /// stick arc, N.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tension_tight: Option<f64>,
    /// Axial force in the driven pulley's stick zone in steady motion, at the middle of
    /// the stick arc, N.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tension_slack: Option<f64>,
    /// ω₂, rad/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub driven_speed: Option<f64>,
    /// c = mass flux / ρ, m/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transport_rate: Option<f64>,
    /// ω of the single pulley (one-pulley scenes), rad/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pulley_speed: Option<f64>,
    /// Axial force at the inflow end (one-pulley scenes), N.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tension_in: Option<f64>,
    /// Axial force at the outflow end (one-pulley scenes), N.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tension_out: Option<f64>,
    /// y of the centreline at the inflow end section (one-pulley scenes), m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y_in: Option<f64>,
    /// y of the centreline at the outflow end section (one-pulley scenes), m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub y_out: Option<f64>,
    /// Lateral run-off velocity of a shell belt, m/s (+z along the drum axes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub runoff_velocity: Option<f64>,
    /// Lateral run-off velocity of a shell belt after its lateral transient, m/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub settled_runoff_velocity: Option<f64>,
    /// Lateral drift of a shell belt per belt revolution, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drift_per_revolution: Option<f64>,
    /// Largest membrane stress along the belt at its edges, Pa (shell).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edge_stress_max: Option<f64>,
    /// Driver pulley quantities.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub driver: Option<PulleySummary>,
    /// Driven pulley quantities.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub driven: Option<PulleySummary>,
    /// The single pulley of a one-pulley scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pulley: Option<PulleySummary>,
}

impl Summary {
    accessors!(Global: global, global_slot;
        YUpperMid => y_upper_mid, YLowerMid => y_lower_mid, TensionUpperMid => tension_upper_mid,
        TensionLowerMid => tension_lower_mid, MomentUpperMid => moment_upper_mid,
        MomentLowerMid => moment_lower_mid, TensionTight => tension_tight, TensionSlack => tension_slack,
        DrivenSpeed => driven_speed, TransportRate => transport_rate, PulleySpeed => pulley_speed,
        TensionIn => tension_in, TensionOut => tension_out, YIn => y_in, YOut => y_out,
        RunoffVelocity => runoff_velocity, SettledRunoffVelocity => settled_runoff_velocity, DriftPerRevolution => drift_per_revolution, EdgeStressMax => edge_stress_max);

    fn pulley_block(&mut self, p: PulleyId) -> &mut Option<PulleySummary> {
        match p {
            PulleyId::Driver => &mut self.driver,
            PulleyId::Driven => &mut self.driven,
            PulleyId::Pulley => &mut self.pulley,
        }
    }

    /// The value of a quantity; `None` if absent.
    pub fn value(&self, q: Quantity) -> Option<f64> {
        match q {
            Quantity::Global(g) => self.global(g),
            Quantity::Pulley(PulleyId::Driver, k) => self.driver.as_ref()?.get(k),
            Quantity::Pulley(PulleyId::Driven, k) => self.driven.as_ref()?.get(k),
            Quantity::Pulley(PulleyId::Pulley, k) => self.pulley.as_ref()?.get(k),
        }
    }

    /// Sets (or, with `None`, removes) a quantity; a pulley block is created on first
    /// use.
    pub fn set_value(&mut self, q: Quantity, value: Option<f64>) {
        match q {
            Quantity::Global(g) => *self.global_slot(g) = value,
            Quantity::Pulley(p, k) => *self.pulley_block(p).get_or_insert_with(PulleySummary::default).slot_mut(k) = value,
        }
    }

    /// The present quantities as (typed id, value), in the order of [`Quantity::ALL`].
    pub fn quantities(&self) -> Vec<(Quantity, f64)> {
        Quantity::ALL.iter().filter_map(|&q| Some((q, self.value(q)?))).collect()
    }

    /// The present scalars as (flat name, value), in the order of [`SCALAR_NAMES`]:
    /// top-level names as is, pulley quantities as `driver.<field>` / `driven.<field>`
    /// / `pulley.<field>`.
    pub fn scalars(&self) -> Vec<(String, f64)> {
        self.quantities().into_iter().map(|(q, v)| (q.name().to_string(), v)).collect()
    }

    /// The scalar of a flat name; `None` if absent or not a summary name.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.value(Quantity::parse(name).ok()?)
    }

    /// Sets (or, with `None`, removes) the scalar of a flat name; a pulley block is
    /// created on first use.
    ///
    /// # Errors
    /// [`ResultError::UnknownQuantity`] (with the nearest name) for a name not in
    /// [`SCALAR_NAMES`].
    pub fn set(&mut self, name: &str, value: Option<f64>) -> Result<(), ResultError> {
        self.set_value(Quantity::parse(name)?, value);
        Ok(())
    }

    /// A summary from (flat name, value) pairs, e.g. the output of
    /// [`Summary::scalars`] after extrapolation.
    ///
    /// # Errors
    /// As [`Summary::set`].
    pub fn from_scalars<'a, I>(scalars: I) -> Result<Summary, ResultError>
    where
        I: IntoIterator<Item = (&'a str, f64)>,
    {
        let mut s = Summary::default();
        for (name, v) in scalars {
            s.set(name, Some(v))?;
        }
        Ok(s)
    }

    /// The summary of the mirror image y → −y of a two-pulley scene (docs/string-drive.md,
    /// "Both rotation senses and both power flows"): without gravity the drive with
    /// (−ω₁, −M₂, d₂) is the mirror image of the one with (ω₁, M₂, d₂). σ still runs
    /// clockwise in the image, so the upper and lower spans swap (y negated, axial
    /// forces and bending moments kept), speeds, transport rate and torques change sign,
    /// the stick-zone forces, arcs and edge values keep theirs, and each contact zone's
    /// start and end swap with their polar angles negated (wrapped into (−π, π]).
    /// One-pulley fields are copied unchanged.
    pub fn mirror_y(&self) -> Summary {
        let neg = |v: Option<f64>| v.map(|x| -x);
        let angle = |v: Option<f64>| {
            v.map(|a| {
                let m = -a;
                if m <= -std::f64::consts::PI { m + 2.0 * std::f64::consts::PI } else { m }
            })
        };
        let pulley = |p: &Option<PulleySummary>| {
            p.as_ref().map(|p| PulleySummary {
                contact_start: angle(p.contact_end),
                contact_end: angle(p.contact_start),
                torque: neg(p.torque),
                edge_force_start: p.edge_force_end,
                edge_force_end: p.edge_force_start,
                edge_pressure_start: p.edge_pressure_end,
                edge_pressure_end: p.edge_pressure_start,
                moment_start: p.moment_end,
                moment_end: p.moment_start,
                stick_slip_angle: angle(p.stick_slip_angle),
                ..p.clone()
            })
        };
        Summary {
            y_upper_mid: neg(self.y_lower_mid),
            y_lower_mid: neg(self.y_upper_mid),
            tension_upper_mid: self.tension_lower_mid,
            tension_lower_mid: self.tension_upper_mid,
            moment_upper_mid: self.moment_lower_mid,
            moment_lower_mid: self.moment_upper_mid,
            driven_speed: neg(self.driven_speed),
            transport_rate: neg(self.transport_rate),
            driver: pulley(&self.driver),
            driven: pulley(&self.driven),
            ..self.clone()
        }
    }

    /// Checks that every present scalar is finite (serde_json would write NaN as
    /// `null`, which readers take for absent).
    ///
    /// # Errors
    /// [`ResultError::NotFinite`] naming the first non-finite quantity.
    pub fn check_finite(&self) -> Result<(), ResultError> {
        match self.quantities().into_iter().find(|(_, v)| !v.is_finite()) {
            Some((q, value)) => Err(ResultError::NotFinite { quantity: q.name().to_string(), value }),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The mirror image swaps the spans and each zone's ends, negates the speeds and
    /// torques, and is its own inverse.
    #[test]
    fn mirror_y_swaps_spans_and_zone_ends() {
        let mut s = Summary::default();
        for (i, name) in SCALAR_NAMES.iter().enumerate() {
            s.set(name, Some(0.1 + 0.01 * i as f64)).unwrap();
        }
        s.set("driver.contact_start", Some(std::f64::consts::PI)).unwrap();
        let m = s.mirror_y();
        assert_eq!(m.get("y_upper_mid"), s.get("y_lower_mid").map(|v| -v));
        assert_eq!(m.get("tension_lower_mid"), s.get("tension_upper_mid"));
        assert_eq!(m.get("tension_tight"), s.get("tension_tight"));
        assert_eq!(m.get("transport_rate"), s.get("transport_rate").map(|v| -v));
        assert_eq!(m.get("driven.torque"), s.get("driven.torque").map(|v| -v));
        assert_eq!(m.get("driven.contact_start"), s.get("driven.contact_end").map(|v| -v));
        assert_eq!(m.get("driver.contact_end"), Some(std::f64::consts::PI));
        assert_eq!(m.get("driver.edge_force_start"), s.get("driver.edge_force_end"));
        assert_eq!(m.get("driver.moment_end"), s.get("driver.moment_start"));
        assert_eq!(m.get("driven.stick_slip_angle"), s.get("driven.stick_slip_angle").map(|v| -v));
        assert_eq!(m.get("driven.stretch_stick"), s.get("driven.stretch_stick"));
        assert_eq!(m.get("driven.slip_arc"), s.get("driven.slip_arc"));
        assert_eq!(m.mirror_y(), s);
    }

    #[test]
    fn names_round_trip_through_set_and_get() {
        let mut s = Summary::default();
        for (i, name) in SCALAR_NAMES.iter().enumerate() {
            s.set(name, Some(i as f64)).unwrap();
        }
        let flat = s.scalars();
        assert_eq!(flat.len(), SCALAR_NAMES.len());
        for (i, (name, v)) in flat.iter().enumerate() {
            assert_eq!(name, SCALAR_NAMES[i]);
            assert_eq!(*v, i as f64);
            assert_eq!(s.get(name), Some(i as f64));
        }
        s.set("driver.torque", None).unwrap();
        assert_eq!(s.get("driver.torque"), None);
        assert_eq!(s.scalars().len(), SCALAR_NAMES.len() - 1);
    }

    /// Every quantity has a unit and a meaning, and the unit follows from its name's
    /// family (so a new quantity cannot be added with the unit of its neighbour).
    #[test]
    fn units_and_meanings_follow_the_names() {
        for q in Quantity::ALL {
            let (name, unit) = (q.name(), q.unit());
            assert!(q.meaning().len() > 10, "{name}");
            let leaf = name.rsplit('.').next().unwrap();
            let expected = if leaf.starts_with("tension") || leaf.starts_with("edge_force") {
                "N"
            } else if leaf.starts_with("edge_pressure") || leaf.starts_with("pressure") {
                "N/m"
            } else if leaf.starts_with("shear_strain") || leaf.starts_with("stretch") {
                "1"
            } else if leaf == "dissipation" {
                "W"
            } else if leaf.starts_with("y_") {
                "m"
            } else if leaf.starts_with("moment") || leaf == "torque" {
                "N·m"
            } else if leaf.ends_with("_speed") {
                "rad/s"
            } else if leaf == "transport_rate" || leaf.ends_with("_velocity") {
                "m/s"
            } else if leaf.starts_with("drift_") {
                "m"
            } else if leaf.ends_with("_stress_max") {
                "Pa"
            } else if leaf.ends_with("_arc") || leaf.starts_with("contact_") || leaf.ends_with("_angle") {
                "rad"
            } else {
                panic!("{name}: no unit family")
            };
            assert_eq!(unit, expected, "{name}");
        }
    }

    #[test]
    fn unknown_names() {
        let mut s = Summary::default();
        let e = s.set("driver.contact_ark", Some(1.0)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "`driver.contact_ark` is not a summary quantity; did you mean `driver.contact_arc`?"
        );
        assert!(s.set("idler.torque", Some(1.0)).is_err());
        assert!(s.set("driver.", Some(1.0)).is_err());
        assert!(s.set("", Some(1.0)).is_err());
        assert_eq!(s.get("y_upper_mid.x"), None);
        assert_eq!(s.get("nonsense"), None);
    }

    #[test]
    fn typed_ids_and_flat_names_agree() {
        for (k, q) in Quantity::ALL.iter().enumerate() {
            assert_eq!(q.index(), k);
            assert_eq!(Quantity::parse(SCALAR_NAMES[k]).unwrap(), *q);
            let expected = match q {
                Quantity::Global(g) => g.name().to_string(),
                Quantity::Pulley(p, x) => format!("{}.{}", p.name(), x.name()),
            };
            assert_eq!(q.name(), expected);
        }
        // Serialised, each quantity sits where its flat name says.
        let mut s = Summary::default();
        for (k, q) in Quantity::ALL.iter().enumerate() {
            s.set_value(*q, Some(k as f64 + 0.5));
        }
        let json = serde_json::to_value(&s).unwrap();
        for (k, name) in SCALAR_NAMES.iter().enumerate() {
            let v = match name.split_once('.') {
                Some((p, f)) => &json[p][f],
                None => &json[*name],
            };
            assert_eq!(v.as_f64(), Some(k as f64 + 0.5), "{name}");
        }
        // Absent stays absent: a two-pulley summary writes no one-pulley names.
        let two = Summary { y_upper_mid: Some(0.1), ..Default::default() };
        assert_eq!(serde_json::to_string(&two).unwrap(), r#"{"y_upper_mid":0.1}"#);
    }

    #[test]
    fn non_finite_is_named() {
        let mut s = Summary {
            y_upper_mid: Some(0.1),
            ..Default::default()
        };
        s.set("driven.slip_arc", Some(f64::NAN)).unwrap();
        let e = s.check_finite().unwrap_err();
        assert!(
            matches!(&e, ResultError::NotFinite { quantity, .. } if quantity == "driven.slip_arc"),
            "{e}"
        );
        assert!(e.to_string().contains("driven.slip_arc"));
    }
}
