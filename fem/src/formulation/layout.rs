//! The registry's face for any 1-D element layout: [`LayoutElement`] (what the static
//! analysis and the solution view need of an element with N unknowns besides assembly)
//! and [`RegisteredElement`] (a registry entry: a [`Formulation`](super::Formulation) on
//! the string layout, or an element on the Cosserat layout).

use std::sync::Arc;

use drive::contour::{Contour, Region};

use super::{Kernel, TermRules, Theory};
use crate::assembly::ElementKernel;
use crate::element::{ElementLayout, COSSERAT, STRING};
use crate::kinematics::{ElementContext, TermParams, NDOF};

/// Unknowns of an element on the Cosserat layout {s, ν, θ} ([`COSSERAT`]).
pub const NDOF_COSSERAT: usize = COSSERAT.dofs();

/// A 1-D element with N local unknowns as the static analysis
/// ([`crate::static_homotopy`]), the solution view ([`crate::FemSolution`]) and the
/// registry use it: the assembly face [`ElementKernel`] plus its name, theory, the
/// integration rules the view recovers forces at, and its axial force at a point.
///
/// Every [`Formulation`](super::Formulation) is one on the string layout (N = 8, through
/// `dyn Kernel`); an element of another layout — the Cosserat rod's {s, ν, θ}, N = 12 —
/// implements [`ElementKernel`] and this trait and is registered with
/// [`super::register_element`] as a [`RegisteredElement::Cosserat`].
pub trait LayoutElement<const N: usize>: ElementKernel<N> {
    /// Registry name (lowercase ASCII letters, digits, `-`).
    fn name(&self) -> &'static str;
    /// One line for listings and reports.
    fn description(&self) -> &'static str;
    /// The belt theory the element discretises (scenes of another theory are answered
    /// `Unsupported`).
    fn theory(&self) -> Theory;
    /// The integration rule of each term: the view recovers the axial force at the
    /// strain rule's points and the contact pressure at the contact rule's points.
    fn rules(&self) -> TermRules;
    /// Labels of the terms assembled for `params` (for reports).
    fn term_labels(&self, params: &TermParams) -> Vec<String>;
    /// Axial force at ξ of an element with the effective local unknowns `q`
    /// ([`Self::effective`]; `el.augmented` is then all false), N.
    fn axial_force_at(&self, el: &ElementContext, q: &[f64; N], xi: f64) -> f64;
    /// The local unknowns the element's energy actually uses: an element with shared
    /// transition slopes ([`ElementKernel::separate_transition_slopes`] false) applies its
    /// map at the flagged nodes of `el.augmented` here (the Kirchhoff rod's augmented map,
    /// docs/fem-rod.md K9); the default is the identity.
    fn effective(&self, _el: &ElementContext, q: &[f64; N]) -> [f64; N] {
        *q
    }
    /// Value and ∂σ of field number `field` (≥ 2: the fields after s and ν, e.g. θ) at σ
    /// on an element of `region` in the tight start state of the static analysis (F11:
    /// the belt on the contour, ν = −δ); the default is 0 and 0.
    fn start_field(&self, _field: usize, _contour: &Contour, _sigma: f64, _region: Region) -> [f64; 2] {
        [0.0; 2]
    }
    /// The element with the section data of `belt` bound that it does not take from the
    /// [`TermParams`] (the Cosserat elements' shear stiffness b₂), or `None` if it needs
    /// nothing more (the default) or `belt` lacks it.
    fn for_belt(&self, _belt: &crate::problem::BeltSection) -> Option<std::sync::Arc<dyn LayoutElement<N>>> {
        None
    }
    /// The element with the augmented-Lagrangian multipliers `multipliers` of its normal
    /// contact (a field over σ, [`super::ContactMultipliers`]; `None`: the plain penalty),
    /// or `None` (the default) if it has penalty contact only (docs/fem-cosserat.md §12.5).
    fn with_contact_multipliers(&self, _multipliers: Option<Arc<super::ContactMultipliers>>) -> Option<Arc<dyn LayoutElement<N>>> {
        None
    }
    /// The multipliers of its normal contact the element holds; `None` (the default):
    /// the plain penalty, λ ≡ 0.
    fn contact_multipliers(&self) -> Option<&super::ContactMultipliers> {
        None
    }
    /// The normal contact traction ⟨λ(σ) − Pγ⟩₊ (N per unit contour length) at σ for the
    /// penalty P and the gap γ (`None`: no pulley in reach): the penalty's P⟨−γ⟩ with
    /// the multipliers of [`Self::contact_multipliers`].
    fn contact_traction(&self, penalty: f64, sigma: f64, gap: Option<f64>) -> f64 {
        super::augmented_traction(self.contact_multipliers().map_or(0.0, |m| m.at(sigma)), penalty, gap)
    }
    /// The shear stiffness b₂ (N) the element holds (a bound Cosserat element), for the
    /// recovery of its contact edges; `None` (the default) for an unshearable element.
    fn shear_stiffness(&self) -> Option<f64> {
        None
    }
    /// Shear strain Γ₂ at ξ of an element with the effective local unknowns `q` (as
    /// [`Self::axial_force_at`]); `None` (the default) for an unshearable element.
    fn shear_strain_at(&self, _el: &ElementContext, _q: &[f64; N], _xi: f64) -> Option<f64> {
        None
    }
    /// The section rotation θ (rad, the director's angle from +x, any branch) at ξ of an
    /// element with a rotation field of its own; `None` (the default) where the section
    /// follows the tangent of the centreline (the Kirchhoff rod: θ is the tangent angle).
    fn rotation_at(&self, _el: &ElementContext, _q: &[f64; N], _xi: f64) -> Option<f64> {
        None
    }
    /// How a friction point of the closed loop's direct steady solve reads its normal
    /// load (`string_drive::steady`, docs/fem-cosserat.md §11.1): the penalty of the gap
    /// at the node ([`FrictionNormal::Nodal`], the default: the string's and the
    /// Kirchhoff rod's cubic ν follows the pulley at the nodes, docs/fem-drive.md §12),
    /// or the penalty pressure the contact term applies at its rule's points
    /// ([`FrictionNormal::Tributary`]: the shear-deformable element; the string's
    /// errors grow with it, 7–250× at 256 elements on `string-drive`, measured). The
    /// open layout always takes the tributary pressure (docs/fem-cosserat.md §12.5).
    fn friction_normal(&self) -> FrictionNormal {
        FrictionNormal::Nodal
    }
}

/// The normal load p of a friction point of the steady drive ([`LayoutElement::friction_normal`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrictionNormal {
    /// p = P⟨−γ̄⟩, γ̄ the mean gap at the node's two element edges (docs/fem-drive.md §12).
    Nodal,
    /// p = the mean penalty pressure P⟨−γ⟩ of the node's two elements over the contact
    /// rule's points, weighted by the elements' halves at the node (docs/fem-cosserat.md
    /// §12.3): what the penalty term applies where the element's ν does not sit on the
    /// pulley at its nodes.
    Tributary,
}

/// A registered formulation of the string layout is a [`LayoutElement`] with 8 unknowns:
/// its name, theory and rules from the [`Formulation`](super::Formulation), the axial force
/// N = dW/dλ at the point's stretch, and the augmented map (K9) of [`ElementContext::effective`].
impl LayoutElement<NDOF> for dyn Kernel {
    fn name(&self) -> &'static str {
        Kernel::name(self)
    }

    fn description(&self) -> &'static str {
        Kernel::description(self)
    }

    fn theory(&self) -> Theory {
        Kernel::theory(self)
    }

    fn rules(&self) -> TermRules {
        Kernel::rules(self)
    }

    fn term_labels(&self, params: &TermParams) -> Vec<String> {
        Kernel::term_labels(self, params)
    }

    #[inline]
    fn axial_force_at(&self, el: &ElementContext, q: &[f64; NDOF], xi: f64) -> f64 {
        Kernel::axial_force(self, el.stretch(&el.fields(q, xi)), el.params.axial_stiffness)
    }

    #[inline]
    fn effective(&self, el: &ElementContext, q: &[f64; NDOF]) -> [f64; NDOF] {
        el.effective(q)
    }
}

/// One entry of the registry: an element of one of the 1-D layouts, found by name.
/// [`crate::solve_problem`] matches on the layout and runs the analysis monomorphised
/// for it (the static analysis takes either; the drive analyses take the string layout).
#[derive(Clone)]
pub enum RegisteredElement {
    /// A [`Formulation`](super::Formulation) on the string layout {s, ν} ([`STRING`], 8
    /// unknowns): the string and the Kirchhoff rod.
    String(Arc<dyn Kernel>),
    /// An element on the Cosserat layout {s, ν, θ} ([`COSSERAT`], 12 unknowns).
    Cosserat(Arc<dyn LayoutElement<NDOF_COSSERAT>>),
}

impl RegisteredElement {
    /// Registry name.
    pub fn name(&self) -> &'static str {
        match self {
            RegisteredElement::String(k) => Kernel::name(k.as_ref()),
            RegisteredElement::Cosserat(k) => k.name(),
        }
    }

    /// One line for listings and reports.
    pub fn description(&self) -> &'static str {
        match self {
            RegisteredElement::String(k) => Kernel::description(k.as_ref()),
            RegisteredElement::Cosserat(k) => k.description(),
        }
    }

    /// The belt theory the element discretises.
    pub fn theory(&self) -> Theory {
        match self {
            RegisteredElement::String(k) => Kernel::theory(k.as_ref()),
            RegisteredElement::Cosserat(k) => k.theory(),
        }
    }

    /// The integration rule of each term.
    pub fn rules(&self) -> TermRules {
        match self {
            RegisteredElement::String(k) => Kernel::rules(k.as_ref()),
            RegisteredElement::Cosserat(k) => k.rules(),
        }
    }

    /// The element's field layout.
    pub fn layout(&self) -> ElementLayout {
        match self {
            RegisteredElement::String(_) => STRING,
            RegisteredElement::Cosserat(k) => k.layout(),
        }
    }

    /// The string-layout formulation, if this entry is one (the drive analyses run on
    /// it only).
    pub fn string_kernel(&self) -> Option<&Arc<dyn Kernel>> {
        match self {
            RegisteredElement::String(k) => Some(k),
            RegisteredElement::Cosserat(_) => None,
        }
    }
}

impl std::fmt::Debug for RegisteredElement {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RegisteredElement").field("name", &self.name()).field("theory", &self.theory()).field("layout", &self.layout()).finish()
    }
}
