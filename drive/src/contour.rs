//! The compound contour g(σ) of a two-pulley drive and its MEL coordinate system
//! (§5 of the reference, eqs. 27 and 38).
//!
//! # Conventions (DESIGN.md)
//! - Pulley centres at (−H/2, 0) (driver, left) and (+H/2, 0) (driven, right);
//!   H = centre distance, R = pulley radius to the belt centreline; lengths in m.
//! - σ ∈ [0, L_geom), L_geom = 2H + 2πR, starts at the top of the driver (−H/2, R) and
//!   runs clockwise:
//!
//!   | region | σ range | shape | α |
//!   |---|---|---|---|
//!   | [`Region::UpperSpan`] | [0, H) | left → right at y = R | 0 |
//!   | [`Region::DrivenArc`] | [H, H + πR) | top → bottom of the driven pulley | 1/R |
//!   | [`Region::LowerSpan`] | [H + πR, 2H + πR) | right → left at y = −R | 0 |
//!   | [`Region::DriverArc`] | [2H + πR, 2H + 2πR) | bottom → top of the driver | 1/R |
//!
//! - t_g is the unit tangent in the direction of increasing σ; n_g is the **outward**
//!   unit normal, n_g = (−t_g,y, t_g,x) (t_g turned 90° counter-clockwise): (0, 1) on the
//!   upper span, radially outward on the arcs, (0, −1) on the lower span. With these
//!   signs eq. (38) holds: ∂σ g = t_g, ∂σ t_g = −α n_g, ∂σ n_g = α t_g.
//! - A point of the belt is r = g(σ) + ν n_g(σ) (eq. 27, planar): ν is the transverse
//!   deflection, positive away from the pulleys; on an arc R + ν is the distance from
//!   the pulley centre, so ν = 0 is contact with the pulley surface of the centreline
//!   contour and the map is one-to-one for ν > −R.
//!
//! Every function accepts any σ ∈ ℝ and wraps it periodically; a non-finite σ or
//! point gives NaN results (never a panic).

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use crate::error::SceneError;

/// The running direction of the belt relative to σ (σ runs clockwise).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// The belt runs along σ: the driver turns clockwise (ω₁ ≥ 0), the upper span moves
    /// in +x.
    Clockwise,
    /// The belt runs against σ: the driver turns counter-clockwise (ω₁ < 0).
    CounterClockwise,
}

impl Direction {
    /// The direction of a driver turning at ω₁ (rad/s, clockwise positive); at rest,
    /// clockwise.
    pub fn of_speed(omega1: f64) -> Self {
        if omega1 < 0.0 { Direction::CounterClockwise } else { Direction::Clockwise }
    }

    /// +1 along σ, −1 against it.
    pub fn sign(self) -> f64 {
        match self {
            Direction::Clockwise => 1.0,
            Direction::CounterClockwise => -1.0,
        }
    }
}

/// One of the two pulleys.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Pulley {
    /// Left pulley, centre (−H/2, 0), turned at the driver speed ω₁.
    Driver,
    /// Right pulley, centre (+H/2, 0), loaded by the driven torque M₂.
    Driven,
}

impl Pulley {
    /// Both pulleys, driver first (the order of the result format).
    pub const ALL: [Pulley; 2] = [Pulley::Driver, Pulley::Driven];

    /// The key of this pulley in the result format (`driver`, `driven`).
    pub fn name(self) -> &'static str {
        match self {
            Pulley::Driver => "driver",
            Pulley::Driven => "driven",
        }
    }
}

/// The four regions of the compound coordinate σ, in the order σ meets them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Region {
    /// σ ∈ [0, H): Cartesian, y = R, running in +x.
    UpperSpan,
    /// σ ∈ [H, H + πR): polar about the driven centre.
    DrivenArc,
    /// σ ∈ [H + πR, 2H + πR): Cartesian, y = −R, running in −x.
    LowerSpan,
    /// σ ∈ [2H + πR, 2H + 2πR): polar about the driver centre.
    DriverArc,
}

impl Region {
    /// All regions in the order of increasing σ.
    pub const ALL: [Region; 4] = [
        Region::UpperSpan,
        Region::DrivenArc,
        Region::LowerSpan,
        Region::DriverArc,
    ];

    /// True for the arcs (α = 1/R), false for the spans (α = 0).
    pub fn is_polar(self) -> bool {
        matches!(self, Region::DrivenArc | Region::DriverArc)
    }

    /// The pulley an arc belongs to; `None` for a span.
    pub fn pulley(self) -> Option<Pulley> {
        match self {
            Region::DrivenArc => Some(Pulley::Driven),
            Region::DriverArc => Some(Pulley::Driver),
            Region::UpperSpan | Region::LowerSpan => None,
        }
    }
}

/// The geometric contour of a deflection-less belt on two equal pulleys: the line
/// g(σ) of eq. (27) with length L_geom = 2H + 2πR.
///
/// Built by [`Contour::new`] (validated) or [`crate::Scene::contour`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Contour {
    radius: f64,
    centre_distance: f64,
}

impl Contour {
    /// A contour with pulley radius R (m, > 0) and centre distance H (m, > 2R).
    ///
    /// # Errors
    /// [`SceneError::NotPositive`] / [`SceneError::NotFinite`] naming
    /// `drive.pulley_radius` or `drive.centre_distance`, or
    /// [`SceneError::PulleysOverlap`] when H ≤ 2R.
    pub fn new(radius: f64, centre_distance: f64) -> Result<Self, SceneError> {
        crate::scene::check_positive("drive.pulley_radius", radius)?;
        crate::scene::check_positive("drive.centre_distance", centre_distance)?;
        if centre_distance <= 2.0 * radius {
            return Err(SceneError::PulleysOverlap {
                centre_distance,
                pulley_radius: radius,
            });
        }
        Ok(Contour {
            radius,
            centre_distance,
        })
    }

    /// Without checks: for a [`crate::Scene`] that has been validated. An invalid
    /// pair gives meaningless numbers, never a panic.
    pub(crate) fn new_unchecked(radius: f64, centre_distance: f64) -> Self {
        Contour {
            radius,
            centre_distance,
        }
    }

    /// Pulley radius R to the belt centreline, m.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Centre distance H, m.
    pub fn centre_distance(&self) -> f64 {
        self.centre_distance
    }

    /// L_geom = 2H + 2πR, m: the period of σ.
    pub fn length(&self) -> f64 {
        2.0 * self.centre_distance + 2.0 * PI * self.radius
    }

    /// σ wrapped into [0, L_geom).
    pub fn wrap(&self, sigma: f64) -> f64 {
        let l = self.length();
        let w = sigma.rem_euclid(l);
        // rem_euclid of a tiny negative number rounds to l itself
        if w >= l {
            0.0
        } else {
            w
        }
    }

    /// The σ at which each region starts, in the order of [`Region::ALL`]:
    /// [0, H, H + πR, 2H + πR]. These are the Cartesian/polar transitions where α
    /// jumps (the driver arc ends at L_geom ≡ 0).
    pub fn transitions(&self) -> [f64; 4] {
        let (h, pr) = (self.centre_distance, PI * self.radius);
        [0.0, h, h + pr, 2.0 * h + pr]
    }

    /// The σ interval [σ₀, σ₁) of a region (σ₁ = L_geom for the driver arc).
    pub fn region_bounds(&self, region: Region) -> (f64, f64) {
        let t = self.transitions();
        match region {
            Region::UpperSpan => (t[0], t[1]),
            Region::DrivenArc => (t[1], t[2]),
            Region::LowerSpan => (t[2], t[3]),
            Region::DriverArc => (t[3], self.length()),
        }
    }

    /// The region containing σ (wrapped periodically; a region owns its start point).
    pub fn region(&self, sigma: f64) -> Region {
        self.locate(sigma).0
    }

    /// Region and local coordinate u = σ − σ₀ ≥ 0 within it.
    fn locate(&self, sigma: f64) -> (Region, f64) {
        let w = self.wrap(sigma);
        let t = self.transitions();
        if w < t[1] {
            (Region::UpperSpan, w)
        } else if w < t[2] {
            (Region::DrivenArc, w - t[1])
        } else if w < t[3] {
            (Region::LowerSpan, w - t[2])
        } else {
            // also NaN lands here and propagates
            (Region::DriverArc, w - t[3])
        }
    }

    /// α(σ) of eq. (38): 0 on the spans, 1/R on the arcs, 1/m.
    pub fn alpha(&self, sigma: f64) -> f64 {
        if self.region(sigma).is_polar() {
            1.0 / self.radius
        } else {
            0.0
        }
    }

    /// ϑ_g(σ), rad: the angle of t_g from +x, continuous on σ ∈ [0, L_geom) (σ wrapped) —
    /// 0 on the upper span, falling by π over the driven arc, −π on the lower span, −2π at
    /// the end of the driver arc, where it jumps back to 0. The reference of the section
    /// rotation θ = ϑ_g + ψ (docs/fem-cosserat.md (C0)); a rotation that is continuous
    /// along the belt is unwrapped to lie within π of it.
    pub fn tangent_angle(&self, sigma: f64) -> f64 {
        let (region, u) = self.locate(sigma);
        match region {
            Region::UpperSpan => 0.0,
            Region::DrivenArc => -u / self.radius,
            Region::LowerSpan => -PI,
            Region::DriverArc => -PI - u / self.radius,
        }
    }

    /// Centre of a pulley, m: (−H/2, 0) for the driver, (+H/2, 0) for the driven.
    pub fn pulley_centre(&self, pulley: Pulley) -> [f64; 2] {
        let half = 0.5 * self.centre_distance;
        match pulley {
            Pulley::Driver => [-half, 0.0],
            Pulley::Driven => [half, 0.0],
        }
    }

    /// g(σ), m: the point of the contour at σ (eq. 27 with ν = 0).
    pub fn g(&self, sigma: f64) -> [f64; 2] {
        let (region, u) = self.locate(sigma);
        self.point_in(region, u)
    }

    /// g(σ) and n_g(σ) from one location of σ: the values of [`Self::g`] and
    /// [`Self::n_g`] (the same arithmetic), for a caller that needs both at a point — an
    /// element's height and position (each location wraps σ by a remainder and an arc
    /// takes a sine and a cosine).
    pub fn point_and_normal(&self, sigma: f64) -> ([f64; 2], [f64; 2]) {
        let (region, u) = self.locate(sigma);
        (self.point_in(region, u), self.normal_in(region, u))
    }

    /// g at the arc length `u` into `region` ([`Self::g`]).
    fn point_in(&self, region: Region, u: f64) -> [f64; 2] {
        let (h, r) = (self.centre_distance, self.radius);
        match region {
            Region::UpperSpan => [-0.5 * h + u, r],
            Region::LowerSpan => [0.5 * h - u, -r],
            Region::DrivenArc | Region::DriverArc => {
                let c = self.pulley_centre(region.pulley().unwrap_or(Pulley::Driver));
                let n = self.normal_in(region, u);
                [c[0] + r * n[0], c[1] + r * n[1]]
            }
        }
    }

    /// t_g(σ) = ∂σ g: unit tangent in the direction of increasing σ (eq. 38).
    pub fn t_g(&self, sigma: f64) -> [f64; 2] {
        let n = self.n_g(sigma);
        // n = (−t_y, t_x)  ⇔  t = (n_y, −n_x)
        [n[1], -n[0]]
    }

    /// n_g(σ): outward unit normal (eq. 38). On an arc with clockwise angle
    /// φ = (σ − σ₀)/R from the arc's start: driven (sin φ, cos φ), driver
    /// (−sin φ, −cos φ).
    pub fn n_g(&self, sigma: f64) -> [f64; 2] {
        let (region, u) = self.locate(sigma);
        self.normal_in(region, u)
    }

    /// n_g at the arc length `u` into `region` ([`Self::n_g`]).
    fn normal_in(&self, region: Region, u: f64) -> [f64; 2] {
        match region {
            Region::UpperSpan => [0.0, 1.0],
            Region::LowerSpan => [0.0, -1.0],
            Region::DrivenArc => {
                let phi = u / self.radius;
                [phi.sin(), phi.cos()]
            }
            Region::DriverArc => {
                let phi = u / self.radius;
                [-phi.sin(), -phi.cos()]
            }
        }
    }

    /// r = g(σ) + ν n_g(σ), m (eq. 27, planar).
    pub fn position(&self, sigma: f64, nu: f64) -> [f64; 2] {
        let g = self.g(sigma);
        let n = self.n_g(sigma);
        [g[0] + nu * n[0], g[1] + nu * n[1]]
    }

    /// The inverse of [`Contour::position`]: (σ, ν) with σ ∈ [0, L_geom) such that
    /// `position(σ, ν) == point`.
    ///
    /// Assignment of a point (x, y), so that every point of the plane has exactly one
    /// answer:
    /// - x > H/2 (the driven pulley's half-plane): polar map about the driven centre,
    ///   ν = |p − c| − R, σ = H + R·φ with φ ∈ [0, π] the clockwise angle from the top;
    /// - x < −H/2: the same about the driver centre, σ = 2H + πR + R·φ, φ ∈ [0, π]
    ///   measured clockwise from the bottom;
    /// - −H/2 ≤ x ≤ H/2 (the strip between the centres): the vertical normal line;
    ///   y ≥ 0 → upper span (σ = x + H/2, ν = y − R), y < 0 → lower span
    ///   (σ = H + πR + H/2 − x, ν = −y − R).
    ///
    /// Both maps agree on the lines x = ±H/2, so the assignment is continuous there;
    /// it is discontinuous only across y = 0 inside the strip (ν = −R, the centre line
    /// between the pulleys) and at the pulley centres, points no belt reaches
    /// (|ν| < R is the physical range). The round trip holds for ν > −R.
    pub fn sigma_nu(&self, point: [f64; 2]) -> (f64, f64) {
        let (h, r) = (self.centre_distance, self.radius);
        let [x, y] = point;
        let half = 0.5 * h;
        if x > half {
            let (dx, dy) = (x - half, y);
            let phi = dx.atan2(dy); // clockwise from +y, in (0, π] here
            (self.wrap(h + r * phi), dx.hypot(dy) - r)
        } else if x < -half {
            let (dx, dy) = (x + half, y);
            let phi = (-dx).atan2(-dy); // clockwise from −y
            (self.wrap(2.0 * h + PI * r + r * phi), dx.hypot(dy) - r)
        } else if y >= 0.0 {
            (self.wrap(x + half), y - r)
        } else {
            (self.wrap(h + PI * r + half - x), -y - r)
        }
    }

    /// Polar angle atan2(y − y_c, x − x_c) of a point about a pulley centre, rad, in
    /// (−π, π] (the convention of `contact_start`/`contact_end` in the result format).
    pub fn polar_angle(&self, pulley: Pulley, point: [f64; 2]) -> f64 {
        let c = self.pulley_centre(pulley);
        (point[1] - c[1]).atan2(point[0] - c[0])
    }
}

/// The three regions of the open contour of a one-pulley scene, in the order σ meets
/// them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OpenRegion {
    /// σ ∈ [0, D): Cartesian, y = R, from the inflow end x = −D in +x.
    InflowSpan,
    /// σ ∈ [D, D + πR): polar about the pulley centre (the origin), clockwise from the
    /// top.
    PulleyArc,
    /// σ ∈ [D + πR, 2D + πR]: Cartesian, y = −R, in −x to the outflow end x = −D.
    OutflowSpan,
}

impl OpenRegion {
    /// All regions in the order of increasing σ.
    pub const ALL: [OpenRegion; 3] = [OpenRegion::InflowSpan, OpenRegion::PulleyArc, OpenRegion::OutflowSpan];
}

/// The open contour g(σ) of a one-pulley scene (Paper C, spec §2.2; DESIGN.md
/// `drive.layout = "one-pulley"`): the pulley of radius R (to the belt centreline) is
/// centred at the origin; σ ∈ [0, 2D + πR] starts at the inflow end (−D, R), runs along
/// the upper side in +x, clockwise round the pulley, and along the lower side in −x to
/// the outflow end (−D, −R). t_g, n_g and α follow the conventions of [`Contour`]
/// (n_g outward, eq. 38: ∂σ t_g = −α n_g). The domain is open: σ is not wrapped; a σ
/// beyond an end continues the end's straight line.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OpenContour {
    radius: f64,
    end_distance: f64,
}

impl OpenContour {
    /// A contour with pulley radius R > 0 and end distance D > 0 (m).
    ///
    /// # Errors
    /// [`SceneError::NotPositive`] / [`SceneError::NotFinite`] naming
    /// `drive.pulley_radius` or `drive.end_distance`.
    pub fn new(radius: f64, end_distance: f64) -> Result<Self, SceneError> {
        crate::scene::check_positive("drive.pulley_radius", radius)?;
        crate::scene::check_positive("drive.end_distance", end_distance)?;
        Ok(OpenContour { radius, end_distance })
    }

    /// Pulley radius R, m.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// End distance D, m.
    pub fn end_distance(&self) -> f64 {
        self.end_distance
    }

    /// L = 2D + πR, m: the length of the domain.
    pub fn length(&self) -> f64 {
        2.0 * self.end_distance + PI * self.radius
    }

    /// The σ at which each region starts: [0, D, D + πR].
    pub fn transitions(&self) -> [f64; 3] {
        [0.0, self.end_distance, self.end_distance + PI * self.radius]
    }

    /// Region and local coordinate u = σ − σ₀ (negative before the inflow end).
    fn locate(&self, sigma: f64) -> (OpenRegion, f64) {
        let t = self.transitions();
        if sigma < t[1] {
            (OpenRegion::InflowSpan, sigma)
        } else if sigma < t[2] {
            (OpenRegion::PulleyArc, sigma - t[1])
        } else {
            // also NaN lands here and propagates
            (OpenRegion::OutflowSpan, sigma - t[2])
        }
    }

    /// The region containing σ (a region owns its start point).
    pub fn region(&self, sigma: f64) -> OpenRegion {
        self.locate(sigma).0
    }

    /// α(σ): 0 on the spans, 1/R on the arc, 1/m.
    pub fn alpha(&self, sigma: f64) -> f64 {
        if self.region(sigma) == OpenRegion::PulleyArc {
            1.0 / self.radius
        } else {
            0.0
        }
    }

    /// n_g(σ): outward unit normal; on the arc (sin φ, cos φ) with φ = (σ − D)/R the
    /// clockwise angle from the top.
    pub fn n_g(&self, sigma: f64) -> [f64; 2] {
        match self.locate(sigma) {
            (OpenRegion::InflowSpan, _) => [0.0, 1.0],
            (OpenRegion::OutflowSpan, _) => [0.0, -1.0],
            (OpenRegion::PulleyArc, u) => {
                let phi = u / self.radius;
                [phi.sin(), phi.cos()]
            }
        }
    }

    /// t_g(σ) = ∂σ g, with n = (−t_y, t_x).
    pub fn t_g(&self, sigma: f64) -> [f64; 2] {
        let n = self.n_g(sigma);
        [n[1], -n[0]]
    }

    /// ϑ_g(σ), rad: the angle of t_g from +x, continuous along σ — 0 on the inflow span,
    /// falling by π over the arc, −π on the outflow span (the end conditions θ = 0 and
    /// θ = −π of a rod on it).
    pub fn tangent_angle(&self, sigma: f64) -> f64 {
        match self.locate(sigma) {
            (OpenRegion::InflowSpan, _) => 0.0,
            (OpenRegion::PulleyArc, u) => -u / self.radius,
            (OpenRegion::OutflowSpan, _) => -PI,
        }
    }

    /// g(σ), m.
    pub fn g(&self, sigma: f64) -> [f64; 2] {
        let (d, r) = (self.end_distance, self.radius);
        match self.locate(sigma) {
            (OpenRegion::InflowSpan, u) => [-d + u, r],
            (OpenRegion::OutflowSpan, u) => [-u, -r],
            (OpenRegion::PulleyArc, _) => {
                let n = self.n_g(sigma);
                [r * n[0], r * n[1]]
            }
        }
    }

    /// r = g(σ) + ν n_g(σ), m (eq. 27, planar).
    pub fn position(&self, sigma: f64, nu: f64) -> [f64; 2] {
        let g = self.g(sigma);
        let n = self.n_g(sigma);
        [g[0] + nu * n[0], g[1] + nu * n[1]]
    }

    /// The inverse of [`OpenContour::position`]: x ≥ 0 maps polar about the origin
    /// (σ = D + R·φ, φ ∈ [0, π] clockwise from the top, ν = |p| − R); x < 0 maps to the
    /// vertical normal line of the upper (y ≥ 0) or lower span. Both maps agree on
    /// x = 0; the round trip holds for ν > −R.
    pub fn sigma_nu(&self, point: [f64; 2]) -> (f64, f64) {
        let (d, r) = (self.end_distance, self.radius);
        let [x, y] = point;
        if x >= 0.0 {
            let phi = x.atan2(y); // clockwise from +y, in [0, π]
            (d + r * phi, x.hypot(y) - r)
        } else if y >= 0.0 {
            (x + d, y - r)
        } else {
            (d + PI * r - x, -y - r)
        }
    }
}

/// The reference line g(σ) a solution is parametrised on: the closed loop of a two-pulley
/// scene ([`Contour`], σ periodic) or the open contour of a one-pulley scene
/// ([`OpenContour`], σ ∈ [0, 2D + πR], not wrapped). The common solution view
/// ([`crate::SolutionView::path`]) and the harness read a solution through it, whatever the
/// layout.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Path {
    /// The closed two-pulley loop.
    Loop(Contour),
    /// The open one-pulley contour.
    Open(OpenContour),
}

impl From<Contour> for Path {
    fn from(c: Contour) -> Path {
        Path::Loop(c)
    }
}

impl From<OpenContour> for Path {
    fn from(c: OpenContour) -> Path {
        Path::Open(c)
    }
}

impl Path {
    /// Length of the σ domain, m: the period L_geom = 2H + 2πR of the loop, or 2D + πR.
    pub fn length(&self) -> f64 {
        match self {
            Path::Loop(c) => c.length(),
            Path::Open(c) => c.length(),
        }
    }

    /// Pulley radius R to the belt centreline, m.
    pub fn radius(&self) -> f64 {
        match self {
            Path::Loop(c) => c.radius(),
            Path::Open(c) => c.radius(),
        }
    }

    /// The loop's contour; `None` for the open contour.
    pub fn as_loop(&self) -> Option<&Contour> {
        match self {
            Path::Loop(c) => Some(c),
            Path::Open(_) => None,
        }
    }

    /// True for an open contour (one-pulley scenes).
    pub fn is_open(&self) -> bool {
        matches!(self, Path::Open(_))
    }

    /// σ in the domain: wrapped into [0, L_geom) on the loop, unchanged on the open
    /// contour (its σ beyond an end continues the end's straight line).
    pub fn wrap(&self, sigma: f64) -> f64 {
        match self {
            Path::Loop(c) => c.wrap(sigma),
            Path::Open(_) => sigma,
        }
    }

    /// r = g(σ) + ν n_g(σ), m (eq. 27, planar).
    pub fn position(&self, sigma: f64, nu: f64) -> [f64; 2] {
        match self {
            Path::Loop(c) => c.position(sigma, nu),
            Path::Open(c) => c.position(sigma, nu),
        }
    }

    /// The inverse map point → (σ, ν) of [`Path::position`].
    pub fn sigma_nu(&self, point: [f64; 2]) -> (f64, f64) {
        match self {
            Path::Loop(c) => c.sigma_nu(point),
            Path::Open(c) => c.sigma_nu(point),
        }
    }

    /// α(σ): 0 on the spans, 1/R on the arcs, 1/m.
    pub fn alpha(&self, sigma: f64) -> f64 {
        match self {
            Path::Loop(c) => c.alpha(sigma),
            Path::Open(c) => c.alpha(sigma),
        }
    }

    /// ϑ_g(σ), rad: the angle of the contour tangent from +x ([`Contour::tangent_angle`],
    /// [`OpenContour::tangent_angle`]).
    pub fn tangent_angle(&self, sigma: f64) -> f64 {
        match self {
            Path::Loop(c) => c.tangent_angle(sigma),
            Path::Open(c) => c.tangent_angle(sigma),
        }
    }

    /// The angle `theta` shifted by a multiple of 2π to lie within π of ϑ_g(σ): a section
    /// rotation unwrapped as [`Contour::tangent_angle`] (on the loop, continuous on
    /// [0, L_geom), jumping by 2π at σ = 0).
    pub fn unwrap_near_tangent(&self, sigma: f64, theta: f64) -> f64 {
        let reference = self.tangent_angle(sigma);
        theta + (2.0 * PI) * ((reference - theta) / (2.0 * PI)).round()
    }

    /// True on an arc (polar region).
    pub fn is_polar(&self, sigma: f64) -> bool {
        self.alpha(sigma) > 0.0
    }

    /// The regions in the order σ meets them: (σ₀, σ₁, short name).
    pub fn regions(&self) -> Vec<(f64, f64, &'static str)> {
        match self {
            Path::Loop(c) => Region::ALL
                .iter()
                .map(|&r| {
                    let (a, b) = c.region_bounds(r);
                    let name = match r {
                        Region::UpperSpan => "upper span",
                        Region::DrivenArc => "driven arc",
                        Region::LowerSpan => "lower span",
                        Region::DriverArc => "driver arc",
                    };
                    (a, b, name)
                })
                .collect(),
            Path::Open(c) => {
                let t = c.transitions();
                vec![(t[0], t[1], "inflow span"), (t[1], t[2], "pulley arc"), (t[2], c.length(), "outflow span")]
            }
        }
    }

    /// The centres of the pulleys, m: driver then driven on the loop, the origin for the
    /// open contour.
    pub fn pulley_centres(&self) -> Vec<[f64; 2]> {
        match self {
            Path::Loop(c) => Pulley::ALL.iter().map(|&p| c.pulley_centre(p)).collect(),
            Path::Open(_) => vec![[0.0, 0.0]],
        }
    }
}

#[cfg(test)]
mod tests {
    //! Eq. (38) by central finite differences, continuity at the transitions,
    //! the (σ, ν) round trip and periodicity. Geometry: R = 0.08 m, H = 0.45 m
    //! (the `string-hanging` scene of DESIGN.md).
    use super::*;

    const R: f64 = 0.08;
    const H: f64 = 0.45;

    /// `point_and_normal` is `g` and `n_g` from one location: the same bits, on every
    /// region, at the transitions and beyond one period (σ wrapped).
    #[test]
    fn point_and_normal_equals_g_and_n_g() {
        let c = Contour::new(R, H).unwrap();
        let l = c.length();
        let mut sigmas: Vec<f64> = (0..=400).map(|k| -0.3 * l + 1.6 * l * k as f64 / 400.0).collect();
        sigmas.extend(c.transitions());
        for sigma in sigmas {
            let (g, n) = c.point_and_normal(sigma);
            assert_eq!(g.map(f64::to_bits), c.g(sigma).map(f64::to_bits), "g at {sigma}");
            assert_eq!(n.map(f64::to_bits), c.n_g(sigma).map(f64::to_bits), "n_g at {sigma}");
        }
    }

    fn contour() -> Contour {
        Contour::new(R, H).unwrap()
    }

    /// Deterministic uniform numbers in [0, 1) (xorshift64*).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
        (a[0] - b[0]).hypot(a[1] - b[1])
    }

    /// ϑ_g is the angle of t_g (cos, sin to round-off), falls with ∂σϑ_g = −α by central
    /// differences inside every region, is continuous at the inner transitions and spans
    /// [0, −2π) round the loop, [0, −π] along the open contour.
    #[test]
    fn tangent_angle_is_the_angle_of_t_g() {
        let open = OpenContour::new(R, 0.5).unwrap();
        for path in [Path::Loop(contour()), Path::Open(open)] {
            let l = path.length();
            let t_g = |s: f64| match path {
                Path::Loop(c) => c.t_g(s),
                Path::Open(c) => c.t_g(s),
            };
            let mut rng = Rng(0x5eed_1234);
            for _ in 0..200 {
                let s = l * (0.001 + 0.998 * rng.next());
                let (th, t) = (path.tangent_angle(s), t_g(s));
                assert!((th.cos() - t[0]).abs() < 1e-14 && (th.sin() - t[1]).abs() < 1e-14, "σ = {s}");
                let d = 1e-7;
                let (a, b) = (s - d, s + d);
                if path.regions().iter().any(|&(x, y, _)| a >= x && b < y) {
                    let fd = (path.tangent_angle(b) - path.tangent_angle(a)) / (2.0 * d);
                    assert!((fd + path.alpha(s)).abs() < 1e-7, "σ = {s}: {fd} against −α = {}", -path.alpha(s));
                }
                assert!(th <= 0.0 && th > -2.0 * PI, "σ = {s}: {th}");
                let theta = th + 0.3 + 6.0 * PI;
                assert!((path.unwrap_near_tangent(s, theta) - (th + 0.3)).abs() < 1e-12);
            }
            for &(a, _, _) in &path.regions()[1..] {
                let jump = path.tangent_angle(a) - path.tangent_angle(a - 1e-12);
                assert!(jump.abs() < 1e-9, "jump {jump} at σ = {a}");
            }
        }
        assert!((OpenContour::new(R, 0.5).unwrap().tangent_angle(1.0 + PI * R) + PI).abs() < 1e-15);
        assert!((contour().tangent_angle(contour().length() - 1e-12) + 2.0 * PI).abs() < 1e-9);
    }

    #[test]
    fn length_and_transitions() {
        let c = contour();
        assert!((c.length() - (2.0 * H + 2.0 * PI * R)).abs() < 1e-15);
        let t = c.transitions();
        assert_eq!(t[0], 0.0);
        for (k, region) in Region::ALL.iter().enumerate() {
            let (a, b) = c.region_bounds(*region);
            assert_eq!(a, t[k]);
            assert_eq!(c.region(a), *region);
            assert_eq!(c.region(0.5 * (a + b)), *region);
        }
        assert_eq!(c.region_bounds(Region::DriverArc).1, c.length());
        // the points named in DESIGN.md
        assert!(dist(c.g(0.0), [-H / 2.0, R]) < 1e-15);
        assert!(dist(c.g(H), [H / 2.0, R]) < 1e-15);
        assert!(dist(c.g(H + 0.5 * PI * R), [H / 2.0 + R, 0.0]) < 1e-15);
        assert!(dist(c.g(H + PI * R), [H / 2.0, -R]) < 1e-15);
        assert!(dist(c.g(2.0 * H + PI * R), [-H / 2.0, -R]) < 1e-15);
        assert!(dist(c.g(2.0 * H + 1.5 * PI * R), [-H / 2.0 - R, 0.0]) < 1e-15);
        assert_eq!(c.t_g(0.1), [1.0, 0.0]);
        assert_eq!(c.n_g(0.1), [0.0, 1.0]);
        assert_eq!(c.n_g(H + PI * R + 0.1), [0.0, -1.0]);
        assert_eq!(c.alpha(0.1), 0.0);
        assert_eq!(c.alpha(H + 0.1), 1.0 / R);
    }

    /// Eq. (38): ∂σ g = t_g, ∂σ t_g = −α n_g, ∂σ n_g = α t_g, checked by central
    /// differences with step h = 1e-6 m at 50 random σ per region (kept ≥ 2h from the
    /// transitions). Truncation error h²/6·|f'''| ≤ h²/(6R³) ≈ 3e-10 (f = t_g, n_g;
    /// 3e-11 for g); round-off ≈ ε·|f|/h ≤ 1e-10: tolerance 1e-8.
    #[test]
    fn eq38_by_finite_differences() {
        let c = contour();
        let h = 1e-6;
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        for region in Region::ALL {
            let (a, b) = c.region_bounds(region);
            for _ in 0..50 {
                let s = a + 2.0 * h + (b - a - 4.0 * h) * rng.next();
                let a_s = c.alpha(s);
                let fd = |f: &dyn Fn(f64) -> [f64; 2]| {
                    let (p, m) = (f(s + h), f(s - h));
                    [(p[0] - m[0]) / (2.0 * h), (p[1] - m[1]) / (2.0 * h)]
                };
                let (t, n) = (c.t_g(s), c.n_g(s));
                let dg = fd(&|x| c.g(x));
                let dt = fd(&|x| c.t_g(x));
                let dn = fd(&|x| c.n_g(x));
                assert!(dist(dg, t) < 1e-8, "{region:?} σ={s}: ∂g {dg:?} vs t {t:?}");
                assert!(
                    dist(dt, [-a_s * n[0], -a_s * n[1]]) < 1e-8,
                    "{region:?} σ={s}: ∂t"
                );
                assert!(
                    dist(dn, [a_s * t[0], a_s * t[1]]) < 1e-8,
                    "{region:?} σ={s}: ∂n"
                );
                // orthonormal, n = t turned +90°
                assert!((t[0].hypot(t[1]) - 1.0).abs() < 1e-14);
                assert!((n[0] - (-t[1])).abs() < 1e-15 && (n[1] - t[0]).abs() < 1e-15);
            }
        }
    }

    /// g, t_g and n_g are continuous at every transition (the contour is C¹; only
    /// α jumps). With ε = 1e-9: |g(σ+ε) − g(σ−ε)| ≤ 2ε, |Δt| ≤ 2ε/R.
    #[test]
    fn continuity_at_transitions() {
        let c = contour();
        let eps = 1e-9;
        let mut ts = c.transitions().to_vec();
        ts.push(c.length());
        for s in ts {
            assert!(dist(c.g(s - eps), c.g(s + eps)) < 2.5 * eps, "g at {s}");
            assert!(
                dist(c.t_g(s - eps), c.t_g(s + eps)) < 2.5 * eps / R + 1e-15,
                "t_g at {s}"
            );
            assert!(
                dist(c.n_g(s - eps), c.n_g(s + eps)) < 2.5 * eps / R + 1e-15,
                "n_g at {s}"
            );
            assert!(c.alpha(s - eps) != c.alpha(s + eps), "α jumps at {s}");
        }
    }

    /// sigma_nu(position(σ, ν)) = (σ, ν) for 2000 random σ and |ν| < R/2.
    #[test]
    fn inverse_map_round_trip() {
        let c = contour();
        let l = c.length();
        let mut rng = Rng(42);
        for _ in 0..2000 {
            let s = l * rng.next();
            let nu = R * (rng.next() - 0.5);
            let (s2, nu2) = c.sigma_nu(c.position(s, nu));
            let ds = (s2 - s).abs();
            let ds = ds.min(l - ds); // periodic distance
            assert!(
                ds < 1e-12 && (nu2 - nu).abs() < 1e-12,
                "σ={s} ν={nu} → σ={s2} ν={nu2}"
            );
            assert!((0.0..l).contains(&s2));
        }
        // exactly at the transitions
        for s in c.transitions() {
            for nu in [-0.3 * R, 0.0, 0.3 * R] {
                let (s2, nu2) = c.sigma_nu(c.position(s, nu));
                let ds = (s2 - s).abs();
                assert!(ds.min(l - ds) < 1e-12 && (nu2 - nu).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn periodic_wrap() {
        let c = contour();
        let l = c.length();
        for s in [0.0, 0.1, H + 0.01, 2.0 * H + PI * R + 0.02] {
            for k in [-3.0, -1.0, 1.0, 7.0] {
                let w = s + k * l;
                assert!(dist(c.g(w), c.g(s)) < 1e-12);
                assert_eq!(c.region(w), c.region(s));
            }
        }
        assert_eq!(c.wrap(l), 0.0);
        assert_eq!(c.wrap(-1e-300), 0.0);
        assert!((0.0..l).contains(&c.wrap(-1e-17)));
        assert!(c.g(f64::NAN)[0].is_nan());
        assert!(c.sigma_nu([f64::NAN, 0.0]).0.is_nan());
        // the pulley centres themselves: no panic, ν = −R
        assert!((c.sigma_nu(c.pulley_centre(Pulley::Driven)).1 + R).abs() < 1e-15);
    }

    #[test]
    fn polar_angles() {
        let c = contour();
        let top_driver = c.g(0.0);
        assert!((c.polar_angle(Pulley::Driver, top_driver) - PI / 2.0).abs() < 1e-15);
        let right_of_driven = c.g(H + 0.5 * PI * R);
        assert!(c.polar_angle(Pulley::Driven, right_of_driven).abs() < 1e-15);
        // exactly on the negative x-axis of the driver: +π (the branch cut of atan2)
        let left_of_driver = [-H / 2.0 - R, 0.0];
        assert_eq!(c.polar_angle(Pulley::Driver, left_of_driver), PI);
        let bottom_of_driven = c.g(H + PI * R);
        assert!((c.polar_angle(Pulley::Driven, bottom_of_driven) + PI / 2.0).abs() < 1e-15);
    }

    #[test]
    fn construction_errors() {
        assert!(matches!(
            Contour::new(0.1, 0.2),
            Err(SceneError::PulleysOverlap { .. })
        ));
        assert!(matches!(
            Contour::new(-0.1, 1.0),
            Err(SceneError::NotPositive { .. })
        ));
        assert!(matches!(
            Contour::new(f64::NAN, 1.0),
            Err(SceneError::NotFinite { .. })
        ));
    }

    /// The open contour of a one-pulley scene: eq. (38) by central differences inside
    /// every region, continuity of g and t_g at the transitions, the ends where spec §2.2
    /// puts them, and the (σ, ν) round trip.
    #[test]
    fn open_contour_geometry() {
        let (r, d) = (0.1, 0.5);
        let c = OpenContour::new(r, d).unwrap();
        assert!((c.length() - (2.0 * d + PI * r)).abs() < 1e-15);
        assert_eq!(c.g(0.0), [-d, r]);
        let end = c.g(c.length());
        assert!((end[0] + d).abs() < 1e-15 && (end[1] + r).abs() < 1e-15, "{end:?}");
        assert_eq!(c.t_g(0.0), [1.0, 0.0]);
        let h = 1e-6;
        for k in 0..200 {
            let sigma = c.length() * (k as f64 + 0.5) / 200.0;
            let (g0, g1) = (c.g(sigma - h), c.g(sigma + h));
            if c.region(sigma - h) != c.region(sigma + h) {
                continue;
            }
            let t = c.t_g(sigma);
            for i in 0..2 {
                assert!(((g1[i] - g0[i]) / (2.0 * h) - t[i]).abs() < 1e-8, "∂σ g at σ = {sigma}");
                let dt = (c.t_g(sigma + h)[i] - c.t_g(sigma - h)[i]) / (2.0 * h);
                assert!((dt + c.alpha(sigma) * c.n_g(sigma)[i]).abs() < 1e-7, "∂σ t_g at σ = {sigma}");
            }
            for nu in [-0.05, 0.0, 0.03] {
                let (s2, n2) = c.sigma_nu(c.position(sigma, nu));
                assert!((s2 - sigma).abs() < 1e-12 && (n2 - nu).abs() < 1e-12, "round trip at σ = {sigma}, ν = {nu}");
            }
        }
        for t in c.transitions() {
            let (a, b) = (c.g(t - 1e-12), c.g(t));
            assert!((a[0] - b[0]).abs() < 1e-10 && (a[1] - b[1]).abs() < 1e-10, "g jumps at σ = {t}");
            let (a, b) = (c.t_g(t - 1e-12), c.t_g(t));
            assert!((a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9, "t_g jumps at σ = {t}");
        }
        assert!(matches!(OpenContour::new(r, 0.0), Err(SceneError::NotPositive { .. })));
    }
}
