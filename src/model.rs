//! The parameter set, its validation (docs/model.md §5) and the assembled model:
//! body, interface, levers of the equations of motion (docs/model.md §3).

use std::fmt;

use crate::body::{Body, MassModel};
use crate::interface::{solve_increasing, Contact, Interface, Law};
use crate::shape::Shape;

/// Which equation of motion (docs/model.md §3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Formulation {
    /// The paper's Eq. 1 (Costa 2012): no `dI/dphi` term.
    Costa,
    /// The paper's Eq. 9 (Lagrangian, energy-consistent). Default.
    ShiftingPivot,
}

/// How the coefficient of restitution is chosen (docs/model.md §3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Restitution {
    /// `eta = 1 - 2 m b² / IO`.
    Housner,
    /// The parameter `eta`.
    Given,
}

/// Whether the body may rock both ways (docs/model.md §7).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum RestraintKind {
    /// Rocks on both toes (the default).
    #[default]
    None,
    /// Held on one side: rotates only with `sgn(theta) = side`.
    OneSided,
}

/// A one-sided restraint at `theta = 0` (docs/model.md §7).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Restraint {
    /// The sign of `theta` allowed, `+1` or `-1`.
    pub side: f64,
    /// Restitution at the restraint, `omega <- -e omega`, in `[0, 1]`.
    pub e: f64,
}

/// Base shape selector (the FMU's `shape` enumeration).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShapeKind {
    SolidRectangle,
    HollowRectangle,
    SolidCircle,
    HollowCircle,
}

/// Mass model selector (the FMU's `massModel` enumeration).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MassKind {
    Prism,
    Lumped,
}

/// Interface law selector (the FMU's `interface` enumeration).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LawKind {
    Rigid,
    Elastic,
    ElastoPlastic,
}

/// Every parameter of docs/model.md §5, by its public name. Fields that the
/// selected shape, mass model or law does not use are ignored.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    pub shape: ShapeKind,
    /// Rectangle depth along the rocking direction, m.
    pub b: f64,
    /// Rectangle width, m.
    pub l: f64,
    /// Hollow rectangle wall thickness, m.
    pub t: f64,
    /// Circle outer radius, m.
    pub ro: f64,
    /// Hollow circle inner radius, m.
    pub ri: f64,
    pub mass_model: MassKind,
    /// Prism height, m.
    pub h: f64,
    /// Prism density, kg/m³.
    pub rho: f64,
    /// Lumped weight, N.
    pub w: f64,
    /// Lumped height of the centre of mass, m.
    pub hg: f64,
    /// Lumped inertia about the centre of mass, kg m².
    pub ic: f64,
    pub interface: LawKind,
    /// Normal stiffness, Pa/m.
    pub kn: f64,
    /// Compressive strength, Pa.
    pub fm: f64,
    pub formulation: Formulation,
    pub restitution: Restitution,
    /// Coefficient of restitution when `restitution = Given`.
    pub eta: f64,
    /// Gravity, m/s².
    pub g: f64,
    /// Initial rotation, rad.
    pub theta0: f64,
    /// Initial angular velocity, rad/s.
    pub omega0: f64,
    /// One-sided rocking (docs/model.md §7).
    pub restraint: RestraintKind,
    /// The sign of `theta` a one-sided body may take, `+1` or `-1`.
    pub side: i32,
    /// Restitution at the restraint, in `[0, 1]`.
    pub e_restraint: f64,
}

impl Default for Params {
    /// A 0.5 m x 1 m x 2.5 m masonry block (1800 kg/m³) on a mortar joint of
    /// kn = 5 GPa/m crushing at fm = 5 MPa, at rest.
    fn default() -> Params {
        Params {
            shape: ShapeKind::SolidRectangle,
            b: 0.5,
            l: 1.0,
            t: 0.1,
            ro: 0.5,
            ri: 0.3,
            mass_model: MassKind::Prism,
            h: 2.5,
            rho: 1800.0,
            w: 1.0e5,
            hg: 1.25,
            ic: 1.0e4,
            interface: LawKind::ElastoPlastic,
            kn: 5.0e9,
            fm: 5.0e6,
            formulation: Formulation::ShiftingPivot,
            restitution: Restitution::Housner,
            eta: 0.9,
            g: 9.81,
            theta0: 0.0,
            omega0: 0.0,
            restraint: RestraintKind::None,
            side: 1,
            e_restraint: 1.0,
        }
    }
}

/// A parameter that violates a condition of docs/model.md §5.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamError {
    /// The public name of the offending variable.
    pub variable: &'static str,
    /// Its value.
    pub value: f64,
    /// The violated condition, in words and numbers.
    pub condition: String,
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} = {}: {}",
            self.variable,
            Num(self.value),
            self.condition
        )
    }
}

/// A value in a message: as Rust writes it (`22072.5`, `100000`) within
/// `[1e-5, 1e16)`, in exponent form outside, where the plain form would
/// spell out hundreds of digits (`1e300`, not a 301-digit integer).
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.0.abs();
        if a == 0.0 || !a.is_finite() || (1e-5..1e16).contains(&a) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

impl std::error::Error for ParamError {}

fn check(
    ok: bool,
    variable: &'static str,
    value: f64,
    condition: impl Into<String>,
) -> Result<(), ParamError> {
    if ok {
        Ok(())
    } else {
        Err(ParamError {
            variable,
            value,
            condition: condition.into(),
        })
    }
}

/// The smallest joint-opening rotation accepted for a flexible interface, rad.
pub const MIN_THETA_JO: f64 = 1e-100;

/// `value`, if it is finite and > 0.
fn positive(variable: &'static str, value: f64) -> Result<f64, ParamError> {
    check(
        value.is_finite() && value > 0.0,
        variable,
        value,
        "must be finite and > 0",
    )?;
    Ok(value)
}

impl Params {
    /// Validate (docs/model.md §5) and assemble the model.
    pub fn build(&self) -> Result<Model, ParamError> {
        positive("g", self.g)?;
        let shape = match self.shape {
            ShapeKind::SolidRectangle => Shape::SolidRectangle {
                b: positive("B", self.b)?,
                l: positive("L", self.l)?,
            },
            ShapeKind::HollowRectangle => {
                let (b, l) = (positive("B", self.b)?, positive("L", self.l)?);
                let t = positive("t", self.t)?;
                let m = b.min(l);
                check(
                    2.0 * t < m,
                    "t",
                    t,
                    format!("must satisfy 2*t < min(B, L) = {}", Num(m)),
                )?;
                Shape::HollowRectangle { b, l, t }
            }
            ShapeKind::SolidCircle => Shape::SolidCircle {
                ro: positive("Ro", self.ro)?,
            },
            ShapeKind::HollowCircle => {
                let (ro, ri) = (positive("Ro", self.ro)?, positive("Ri", self.ri)?);
                check(
                    ri < ro,
                    "Ri",
                    ri,
                    format!("must satisfy Ri < Ro = {}", Num(ro)),
                )?;
                Shape::HollowCircle { ro, ri }
            }
        };
        let mass_model = match self.mass_model {
            MassKind::Prism => MassModel::Prism {
                h: positive("H", self.h)?,
                rho: positive("rho", self.rho)?,
            },
            MassKind::Lumped => {
                let (w, hg) = (positive("W", self.w)?, positive("hG", self.hg)?);
                check(
                    self.ic.is_finite() && self.ic >= 0.0,
                    "Ic",
                    self.ic,
                    "must be finite and >= 0",
                )?;
                MassModel::Lumped { w, hg, ic: self.ic }
            }
        };
        // Sizes that pass one by one can still overflow together.
        let (area, is) = (shape.area(), shape.second_moment());
        // overflow: the outer size; a vanishing hollow section: the wall
        let (size_name, size) = match (self.shape, area.is_finite() && is.is_finite()) {
            (ShapeKind::HollowRectangle, true) => ("t", self.t),
            (ShapeKind::HollowCircle, true) => ("Ri", self.ri),
            (ShapeKind::SolidRectangle | ShapeKind::HollowRectangle, _) => ("B", self.b),
            (ShapeKind::SolidCircle | ShapeKind::HollowCircle, _) => ("Ro", self.ro),
        };
        check(
            area.is_finite() && is.is_finite() && area > 0.0 && is > 0.0,
            size_name,
            size,
            format!(
                "the section's area A = {} m2 and second moment Is = {} m4 must be finite and > 0",
                Num(area),
                Num(is)
            ),
        )?;
        let body = Body::new(&shape, mass_model, self.g);
        // A prism's weight is derived: name what the user set, with its value.
        if self.mass_model == MassKind::Prism {
            check(
                body.weight.is_finite() && body.weight > 0.0,
                "rho",
                self.rho,
                format!(
                    "the weight W = rho*g*A*H = {} N must be finite and > 0",
                    Num(body.weight)
                ),
            )?;
        }
        // Derived values of the body (docs/model.md §1) that overflow make the
        // equations of motion meaningless: name the derived variable.
        check(
            body.mass.is_finite() && body.mass > 0.0,
            "mass",
            body.mass,
            format!(
                "the mass W/g must be finite and > 0 (W = {} N, g = {} m/s2)",
                Num(body.weight),
                Num(self.g)
            ),
        )?;
        check(
            body.io.is_finite() && body.io > 0.0,
            "IO",
            body.io,
            format!(
                "the inertia about the toe Ic + m*R0^2 must be finite and > 0 (Ic = {} kg m2, m = {} kg, R0 = {} m)",
                Num(body.ic),
                Num(body.mass),
                Num(body.r0)
            ),
        )?;
        let law = match self.interface {
            LawKind::Rigid => Law::Rigid,
            LawKind::Elastic => Law::Elastic {
                kn: positive("kn", self.kn)?,
            },
            LawKind::ElastoPlastic => {
                positive("kn", self.kn)?;
                check(
                    self.fm > 0.0 && !self.fm.is_nan(),
                    "fm",
                    self.fm,
                    "must be > 0 (inf for no crushing)",
                )?;
                let fa = self.fm * shape.area();
                check(
                    body.weight < fa,
                    "fm",
                    self.fm,
                    format!(
                        "the section crushes at rest: must satisfy W < fm*A, W = {} N, fm*A = {} N",
                        Num(body.weight),
                        Num(fa)
                    ),
                )?;
                if self.fm.is_infinite() {
                    Law::Elastic { kn: self.kn }
                } else {
                    Law::ElastoPlastic {
                        kn: self.kn,
                        fm: self.fm,
                    }
                }
            }
        };
        if law != Law::Rigid {
            let kis = self.kn * shape.second_moment();
            let whg = body.weight * body.hg;
            check(
                kis > whg,
                "kn",
                self.kn,
                format!("the rest position is unstable: must satisfy kn*Is > W*hG, kn*Is = {} N m, W*hG = {} N m", Num(kis), Num(whg)),
            )?;
        }
        let eta = match self.restitution {
            Restitution::Housner => body.eta_housner(),
            Restitution::Given => {
                check(
                    (0.0..=1.0).contains(&self.eta),
                    "eta",
                    self.eta,
                    "must be in [0, 1]",
                )?;
                self.eta
            }
        };
        check(
            self.theta0.is_finite(),
            "theta",
            self.theta0,
            "must be finite",
        )?;
        check(
            self.omega0.is_finite(),
            "omega",
            self.omega0,
            "must be finite",
        )?;
        let restraint = self.restraint()?;
        let interface = Interface::new(shape, law, body.weight);
        if law != Law::Rigid {
            // Below this the integrator's scales (tolerances of order
            // rtol thetaJo) leave the floating-point range; no physical
            // interface comes near it (thetaJo = 2W/(kn A D)).
            check(
                interface.theta_jo() >= MIN_THETA_JO,
                "kn",
                self.kn,
                format!(
                    "the joint opens at thetaJo = {:e} rad, which must be >= {MIN_THETA_JO:e} rad: the interface is too stiff for the weight W = {:e} N",
                    interface.theta_jo(),
                    body.weight
                ),
            )?;
        }
        let mut model = Model {
            body,
            interface,
            formulation: self.formulation,
            eta,
            theta_ov: body.alpha,
            restraint,
        };
        model.theta_ov = model.find_theta_ov();
        check(
            model.theta_ov.is_finite() && model.theta_ov > 0.0,
            "thetaOv",
            model.theta_ov,
            "the overturning rotation must be finite and > 0 (parameters out of floating-point range)",
        )?;
        check(
            self.theta0.abs() < model.theta_ov,
            "theta",
            self.theta0,
            format!(
                "the initial rotation must satisfy |theta| < thetaOv = {}",
                model.theta_ov
            ),
        )?;
        Ok(model)
    }

    /// The restraint of docs/model.md §7 and its checks (docs/model.md §8):
    /// `side` is `±1`, `eRestraint` in `[0, 1]`, and the start value lies on
    /// the allowed side (`restraintViolated`).
    fn restraint(&self) -> Result<Option<Restraint>, ParamError> {
        if self.restraint == RestraintKind::None {
            return Ok(None);
        }
        check(
            self.side == 1 || self.side == -1,
            "side",
            self.side as f64,
            "must be 1 or -1",
        )?;
        check(
            (0.0..=1.0).contains(&self.e_restraint),
            "eRestraint",
            self.e_restraint,
            "must be in [0, 1]",
        )?;
        let side = self.side as f64;
        check(
            side * self.theta0 >= 0.0,
            "theta",
            self.theta0,
            format!("restraintViolated: a one-sided body with side = {side} must start with side*theta >= 0"),
        )?;
        Ok(Some(Restraint {
            side,
            e: self.e_restraint,
        }))
    }
}

/// Levers and inertia of the equation of motion at one rotation (docs/model.md §3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Levers {
    /// Lever of the weight about the shifted pivot, `hW`, m.
    pub hw: f64,
    /// Lever of the ground inertia, `hg`, m.
    pub hg: f64,
    /// Inertia about the shifted pivot `I(phi)`, kg m².
    pub inertia: f64,
    /// `dI/dphi`, kg m²/rad.
    pub dinertia: f64,
    /// `dhW/dphi = -hg - af' cos(phi)`, m/rad.
    pub dhw: f64,
    /// `dhg/dphi = hW - af' sin(phi)`, m/rad.
    pub dhg: f64,
}

/// A validated model: body, interface and the constants of the motion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Model {
    pub body: Body,
    pub interface: Interface,
    pub formulation: Formulation,
    /// Coefficient of restitution applied at every impact.
    pub eta: f64,
    /// Overturning rotation at the weight, rad.
    pub theta_ov: f64,
    /// One-sided rocking (docs/model.md §7), `None`: both ways.
    pub restraint: Option<Restraint>,
}

impl Model {
    /// `hW, hg, I, dI/dphi` and the derivatives of the levers at
    /// `phi = |theta|` for the contact `c` there (docs/model.md §3).
    #[inline]
    pub fn levers(&self, phi: f64, c: &Contact) -> Levers {
        let b = &self.body;
        let (s, co) = crate::trig::sin_cos(phi);
        // sin(alpha - phi), cos(alpha - phi)
        let sap = b.sin_alpha * co - b.cos_alpha * s;
        let cap = b.cos_alpha * co + b.sin_alpha * s;
        let af = c.af;
        let r2 = b.r0 * b.r0 + af * af - 2.0 * b.r0 * af * b.sin_alpha;
        let hw = b.r0 * sap - af * co;
        let hg = b.r0 * cap - af * s;
        Levers {
            hw,
            hg,
            inertia: b.ic + b.mass * r2,
            dinertia: -2.0 * b.mass * (b.r0 * b.sin_alpha - af) * c.daf,
            // d/dphi of R0 sin(alpha - phi) - af cos(phi) and of
            // R0 cos(alpha - phi) - af sin(phi)
            dhw: -hg - c.daf * co,
            dhg: hw - c.daf * s,
        }
    }

    /// Restoring moment `MR = W hW(phi)` and its derivative `dMR/dphi`, N m
    /// and N m/rad (docs/model.md §3).
    pub fn restoring_moment(&self, phi: f64) -> (f64, f64) {
        let c = self.interface.contact(phi);
        let l = self.levers(phi, &c);
        (self.body.weight * l.hw, self.body.weight * l.dhw)
    }

    /// The contact at `phi` under the apparent weight `n` (N, docs/model.md
    /// §6.1), with `daf/dN` (m/N) in place of nothing: `(contact, daf/dN)`.
    /// At `n = W` exactly, the contact at the weight; at `n <= 0` the limit
    /// `n -> 0+` of [`Interface::contact_loaded`] with `daf/dN = 0` (it grows
    /// without bound as N falls to 0; only the `liftOff` instant asks).
    pub fn contact_loaded(&self, phi: f64, n: f64) -> (Contact, f64) {
        if n <= 0.0 {
            return (self.interface.contact_loaded(phi, n, f64::NAN).0, 0.0);
        }
        if n == self.body.weight || self.interface.law() == Law::Rigid {
            let c = self.interface.contact(phi);
            let (_, xel) = self.interface.contact_loaded(phi, n, c.a);
            return (c, (xel - c.af) / n);
        }
        let (c, xel) = self.interface.contact_loaded(phi, n, f64::NAN);
        (c, (xel - c.af) / n)
    }

    /// The smallest relative margin of the apparent weight `N = W + m av`
    /// to the range of docs/model.md §6.5, positive inside it: `liftOff` at
    /// `N = 0` (`N/W`, all a rigid bed has), `restUnstable` at `kn Is/hG`,
    /// `baseCrushing` at `fm A`. Model Exchange's range indicator, planar and
    /// in space.
    pub fn range_margin(&self, av: f64) -> f64 {
        let b = &self.body;
        let n = b.weight + b.mass * av;
        let shape = self.interface.shape();
        let unstable = |kn: f64| 1.0 - n / (kn * shape.second_moment() / b.hg);
        match self.interface.law() {
            Law::Rigid => n / b.weight,
            Law::Elastic { kn } => (n / b.weight).min(unstable(kn)),
            Law::ElastoPlastic { kn, fm } => (n / b.weight)
                .min(unstable(kn))
                .min(1.0 - n / (fm * shape.area())),
        }
    }

    /// Overturning rotation under the apparent weight `n` (N): the first root
    /// of `hW(phi, N)` (docs/model.md §6.1); `alpha` for the rigid law.
    /// At `n <= 0` the limit `n -> 0+`, the rigid body's `alpha`.
    pub fn theta_ov_at(&self, n: f64) -> f64 {
        if n == self.body.weight {
            return self.theta_ov;
        }
        if n <= 0.0 {
            return self.body.alpha;
        }
        self.find_theta_ov_at(n)
    }

    fn find_theta_ov(&self) -> f64 {
        self.find_theta_ov_at(self.body.weight)
    }

    /// The first root of `hW(phi) = 0` for `phi > 0` (docs/model.md §3): alpha for
    /// the rigid law; otherwise a geometric scan from far below the first
    /// threshold up to alpha, where `hW = -af cos(alpha) < 0`, refined by bisection.
    fn find_theta_ov_at(&self, n: f64) -> f64 {
        let alpha = self.body.alpha;
        if self.interface.law() == Law::Rigid {
            return alpha;
        }
        let contact = |phi: f64| {
            if n == self.body.weight {
                self.interface.contact(phi)
            } else {
                self.interface.contact_loaded(phi, n, f64::NAN).0
            }
        };
        let hw = |phi: f64| self.levers(phi, &contact(phi)).hw;
        let first = self
            .interface
            .theta_jo()
            .min(self.interface.theta_c())
            .min(alpha)
            * (n / self.body.weight).min(1.0);
        let start = first * 1e-6;
        let n = 400;
        let ratio = (alpha / start).powf(1.0 / n as f64);
        let mut prev = start;
        for i in 1..=n {
            let phi = if i == n { alpha } else { start * ratio.powi(i) };
            if hw(phi) <= 0.0 {
                return solve_increasing(|p| -hw(p), prev, phi);
            }
            prev = phi;
        }
        alpha
    }
}
