//! The named scalars of a solution (`summary` of DESIGN.md's result format).
//!
//! A quantity that a scene's effects do not produce is `None` and is *absent* from
//! the JSON (never `0`, never `null`). The verification harness compares summaries
//! by the flat names of [`SCALAR_NAMES`] (`y_upper_mid`, `driver.contact_arc`, ...).
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
//! - `tension_tight`/`tension_slack`: larger/smaller span tension in steady motion, N;
//! - `driven_speed`: ω₂, rad/s, clockwise positive;
//! - `transport_rate`: c = mass flux / ρ, m/s (unstretched length per unit time).

use serde::{Deserialize, Serialize};

use crate::error::ResultError;
use crate::suggest::nearest;

/// Every flat name [`Summary::scalars`] can produce, in its order.
pub const SCALAR_NAMES: [&str; 26] = [
    "y_upper_mid",
    "y_lower_mid",
    "tension_upper_mid",
    "tension_lower_mid",
    "moment_upper_mid",
    "moment_lower_mid",
    "tension_tight",
    "tension_slack",
    "driven_speed",
    "transport_rate",
    "driver.contact_arc",
    "driver.contact_start",
    "driver.contact_end",
    "driver.stick_arc",
    "driver.slip_arc",
    "driver.torque",
    "driver.edge_force_start",
    "driver.edge_force_end",
    "driven.contact_arc",
    "driven.contact_start",
    "driven.contact_end",
    "driven.stick_arc",
    "driven.slip_arc",
    "driven.torque",
    "driven.edge_force_start",
    "driven.edge_force_end",
];

/// Contact quantities of one pulley (`summary.driver`, `summary.driven`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
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
    /// Concentrated normal reaction at the first contact point, N.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edge_force_start: Option<f64>,
    /// Concentrated normal reaction at the last contact point, N.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub edge_force_end: Option<f64>,
}

impl PulleySummary {
    /// The field names, in the order of the result format.
    pub const NAMES: [&'static str; 8] = [
        "contact_arc",
        "contact_start",
        "contact_end",
        "stick_arc",
        "slip_arc",
        "torque",
        "edge_force_start",
        "edge_force_end",
    ];

    fn slots(&self) -> [&Option<f64>; 8] {
        [
            &self.contact_arc,
            &self.contact_start,
            &self.contact_end,
            &self.stick_arc,
            &self.slip_arc,
            &self.torque,
            &self.edge_force_start,
            &self.edge_force_end,
        ]
    }

    fn slots_mut(&mut self) -> [&mut Option<f64>; 8] {
        [
            &mut self.contact_arc,
            &mut self.contact_start,
            &mut self.contact_end,
            &mut self.stick_arc,
            &mut self.slip_arc,
            &mut self.torque,
            &mut self.edge_force_start,
            &mut self.edge_force_end,
        ]
    }
}

/// Named scalars of one solution; see the module docs for units and signs.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
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
    /// Larger span tension in steady motion, N.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tension_tight: Option<f64>,
    /// Smaller span tension in steady motion, N.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tension_slack: Option<f64>,
    /// ω₂, rad/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub driven_speed: Option<f64>,
    /// c = mass flux / ρ, m/s.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transport_rate: Option<f64>,
    /// Driver pulley quantities.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub driver: Option<PulleySummary>,
    /// Driven pulley quantities.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub driven: Option<PulleySummary>,
}

impl Summary {
    fn top_slots(&self) -> [&Option<f64>; 10] {
        [
            &self.y_upper_mid,
            &self.y_lower_mid,
            &self.tension_upper_mid,
            &self.tension_lower_mid,
            &self.moment_upper_mid,
            &self.moment_lower_mid,
            &self.tension_tight,
            &self.tension_slack,
            &self.driven_speed,
            &self.transport_rate,
        ]
    }

    fn top_slots_mut(&mut self) -> [&mut Option<f64>; 10] {
        [
            &mut self.y_upper_mid,
            &mut self.y_lower_mid,
            &mut self.tension_upper_mid,
            &mut self.tension_lower_mid,
            &mut self.moment_upper_mid,
            &mut self.moment_lower_mid,
            &mut self.tension_tight,
            &mut self.tension_slack,
            &mut self.driven_speed,
            &mut self.transport_rate,
        ]
    }

    /// The present scalars as (flat name, value), in the order of [`SCALAR_NAMES`]:
    /// top-level names as is, pulley quantities as `driver.<field>` / `driven.<field>`.
    pub fn scalars(&self) -> Vec<(String, f64)> {
        let mut out = Vec::new();
        for (name, slot) in SCALAR_NAMES.iter().zip(self.top_slots()) {
            if let Some(v) = *slot {
                out.push((name.to_string(), v));
            }
        }
        for (prefix, pulley) in [("driver", &self.driver), ("driven", &self.driven)] {
            if let Some(p) = pulley {
                for (name, slot) in PulleySummary::NAMES.iter().zip(p.slots()) {
                    if let Some(v) = *slot {
                        out.push((format!("{prefix}.{name}"), v));
                    }
                }
            }
        }
        out
    }

    /// The scalar of a flat name; `None` if absent or not a summary name.
    pub fn get(&self, name: &str) -> Option<f64> {
        if let Some((prefix, field)) = name.split_once('.') {
            let pulley = match prefix {
                "driver" => self.driver.as_ref()?,
                "driven" => self.driven.as_ref()?,
                _ => return None,
            };
            let k = PulleySummary::NAMES.iter().position(|n| *n == field)?;
            return *pulley.slots()[k];
        }
        let k = SCALAR_NAMES[..10].iter().position(|n| *n == name)?;
        *self.top_slots()[k]
    }

    /// Sets (or, with `None`, removes) the scalar of a flat name; a pulley block is
    /// created on first use.
    ///
    /// # Errors
    /// [`ResultError::UnknownQuantity`] (with the nearest name) for a name not in
    /// [`SCALAR_NAMES`].
    pub fn set(&mut self, name: &str, value: Option<f64>) -> Result<(), ResultError> {
        let unknown = || ResultError::UnknownQuantity {
            name: name.to_string(),
            suggestion: nearest(name, SCALAR_NAMES.iter().copied()),
        };
        if let Some((prefix, field)) = name.split_once('.') {
            let k = PulleySummary::NAMES
                .iter()
                .position(|n| *n == field)
                .ok_or_else(unknown)?;
            let pulley = match prefix {
                "driver" => &mut self.driver,
                "driven" => &mut self.driven,
                _ => return Err(unknown()),
            };
            let block = pulley.get_or_insert_with(PulleySummary::default);
            if let Some(slot) = block.slots_mut().into_iter().nth(k) {
                *slot = value;
            }
            return Ok(());
        }
        let k = SCALAR_NAMES[..10]
            .iter()
            .position(|n| *n == name)
            .ok_or_else(unknown)?;
        if let Some(slot) = self.top_slots_mut().into_iter().nth(k) {
            *slot = value;
        }
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

    /// Checks that every present scalar is finite (serde_json would write NaN as
    /// `null`, which readers take for absent).
    ///
    /// # Errors
    /// [`ResultError::NotFinite`] naming the first non-finite quantity.
    pub fn check_finite(&self) -> Result<(), ResultError> {
        match self.scalars().into_iter().find(|(_, v)| !v.is_finite()) {
            Some((quantity, value)) => Err(ResultError::NotFinite { quantity, value }),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn unknown_names() {
        let mut s = Summary::default();
        let e = s.set("driver.contact_ark", Some(1.0)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "`driver.contact_ark` is not a summary quantity; did you mean `driver.contact_arc`?"
        );
        assert!(s.set("idler.torque", Some(1.0)).is_err());
        assert!(s.set("", Some(1.0)).is_err());
        assert_eq!(s.get("y_upper_mid.x"), None);
        assert_eq!(s.get("nonsense"), None);
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
