//! Shared by the string-drive tests (`string_drive.rs`, `string_drive_quadrants.rs`).

use std::f64::consts::PI;

use bvp::analytical::belt_creep::CreepSolution;
use drive::Summary;

/// The quantities belt-creep theory gives in every quadrant of the drive, as
/// (name, the summary's value, the closed form's): the stick-zone forces, ω₂, c, both
/// slip arcs, the driven stick arc π − slip arc and both torques.
pub fn creep_checks(s: &Summary, e: &CreepSolution) -> [(&'static str, f64, f64); 9] {
    let (r, n) = (s.driver.as_ref().unwrap(), s.driven.as_ref().unwrap());
    [
        ("tension_tight", s.tension_tight.unwrap(), e.tension_tight),
        ("tension_slack", s.tension_slack.unwrap(), e.tension_slack),
        ("driven_speed", s.driven_speed.unwrap(), e.driven_speed),
        ("transport_rate", s.transport_rate.unwrap(), e.transport_rate),
        ("driver slip arc", r.slip_arc.unwrap(), e.slip_arc),
        ("driven slip arc", n.slip_arc.unwrap(), e.slip_arc),
        ("driven stick arc", n.stick_arc.unwrap(), PI - e.slip_arc),
        ("driven torque", n.torque.unwrap(), e.driven_torque),
        ("driver torque", r.torque.unwrap(), e.driver_torque),
    ]
}
