//! A linear n-storey shear building under ground acceleration and floor
//! forces, integrated exactly (no FMI).
//!
//! Floor i (1-based, i = 1..n) has the lumped mass `m[i]` (kg) and moves
//! horizontally by `u[i]` (m) relative to the ground; storey i, between
//! floor i-1 (the ground for i = 1) and floor i, has the lateral stiffness
//! `k[i]` (N/m). With `M = diag(m)`, the tridiagonal `K` and a damping matrix
//! `C` (modal or Rayleigh), the equations of motion in relative coordinates
//! are
//!
//! ```text
//! M u'' + C u' + K u = -M 1 ag(t) + Fx(t)
//! ```
//!
//! with `ag` the ground acceleration (m/s2) and `Fx[i]` (N) the horizontal
//! external force on floor i, positive along +x. The absolute acceleration
//! of floor i is `a[i] = u''[i] + ag = (Fx - C u' - K u)[i] / m[i]`.
//!
//! A vertical force on a floor does no work on a purely lateral model: it is
//! not an input of this crate (the FMU accepts `Fz` for coupling and ignores
//! it).
//!
//! Over a step of length h with inputs linear in time, `w(t0 + s) = w0 + s
//! w1`, the state `x = (u, u')` obeys `x' = A x + B w`, and the augmented
//! system `(x, w, w1)' = Z (x, w, w1)` with `Z = [[A, B, 0], [0, 0, I], [0,
//! 0, 0]]` is autonomous: `exp(Z h)` maps the state at the start of the step
//! to its end with no truncation error (the only error is the rounding of
//! the matrix exponential, nalgebra's Pade 13 with scaling and squaring).

use nalgebra::{DMatrix, DVector, SymmetricEigen};

/// Most storeys a frame may have (the FMU's arrays have this length).
pub const MAX_STOREYS: usize = 20;

/// How the damping matrix `C` is built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Damping {
    /// The ratio `zeta` (of critical) in every mode: `C = M Phi diag(2 zeta
    /// omega_j) Phi^T M` with the mass-normalised modes `Phi`.
    Modal { zeta: f64 },
    /// `C = alpha M + beta K`, `alpha` in 1/s, `beta` in s (mode j then has
    /// the ratio `alpha / (2 omega_j) + beta omega_j / 2`).
    Rayleigh { alpha: f64, beta: f64 },
}

/// A state of the frame: time and floor displacements and velocities
/// relative to the ground (entries past `n` stay 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State {
    /// Time, s.
    pub t: f64,
    /// Floor displacements relative to the ground, m.
    pub u: [f64; MAX_STOREYS],
    /// Floor velocities relative to the ground, m/s.
    pub v: [f64; MAX_STOREYS],
}

impl State {
    /// At rest at time `t`.
    pub fn at_rest(t: f64) -> State {
        State {
            t,
            u: [0.0; MAX_STOREYS],
            v: [0.0; MAX_STOREYS],
        }
    }
}

/// The loads at one instant (or their time derivatives).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Load {
    /// Ground acceleration, m/s2 (for a rate: m/s3).
    pub ag: f64,
    /// Horizontal force on each floor, N, +x (for a rate: N/s).
    pub fx: [f64; MAX_STOREYS],
}

impl Load {
    pub const ZERO: Load = Load {
        ag: 0.0,
        fx: [0.0; MAX_STOREYS],
    };
}

/// Time derivatives of the floor responses at an instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rates {
    /// `u'` (m/s) and `u''` (m/s2).
    pub u: [[f64; MAX_STOREYS]; 2],
    /// `v'` (m/s2) and `v''` (m/s3).
    pub v: [[f64; MAX_STOREYS]; 2],
    /// `a'` (m/s3) and `a''` (m/s4) of the absolute acceleration.
    pub a: [[f64; MAX_STOREYS]; 2],
}

/// A shear building: its matrices and modes.
#[derive(Clone, Debug)]
pub struct Frame {
    n: usize,
    mass: DVector<f64>,
    stiffness: DMatrix<f64>,
    damping: DMatrix<f64>,
    /// Natural circular frequencies, rad/s, ascending.
    omega: Vec<f64>,
    /// `x' = A x + B w`, `x = (u, u')`, `w = (ag, Fx[1..n])`.
    a: DMatrix<f64>,
    b: DMatrix<f64>,
}

fn check_positive(name: &str, i: usize, x: f64, unit: &str) -> Result<(), String> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(format!(
            "{name}[{}] = {x} {unit}: must be finite and > 0",
            i + 1
        ))
    }
}

impl Frame {
    /// A frame of `m.len()` storeys; `Err` names the offending parameter
    /// (`n`, `m[i]`, `k[i]`, `zeta`, `rayleighAlpha`, `rayleighBeta`).
    pub fn new(m: &[f64], k: &[f64], damping: Damping) -> Result<Frame, String> {
        let n = m.len();
        if !(1..=MAX_STOREYS).contains(&n) {
            return Err(format!(
                "n = {n}: the frame must have 1 to {MAX_STOREYS} storeys"
            ));
        }
        if k.len() != n {
            return Err(format!("{} storey stiffnesses for n = {n} floors", k.len()));
        }
        for (i, &x) in m.iter().enumerate() {
            check_positive("m", i, x, "kg")?;
        }
        for (i, &x) in k.iter().enumerate() {
            check_positive("k", i, x, "N/m")?;
        }
        match damping {
            Damping::Modal { zeta } => {
                if !(zeta.is_finite() && zeta >= 0.0) {
                    return Err(format!("zeta = {zeta}: must be finite and >= 0"));
                }
            }
            Damping::Rayleigh { alpha, beta } => {
                if !(alpha.is_finite() && alpha >= 0.0) {
                    return Err(format!(
                        "rayleighAlpha = {alpha} 1/s: must be finite and >= 0"
                    ));
                }
                if !(beta.is_finite() && beta >= 0.0) {
                    return Err(format!("rayleighBeta = {beta} s: must be finite and >= 0"));
                }
            }
        }
        let mass = DVector::from_column_slice(m);
        let stiffness = stiffness_matrix(k);
        // Modes from the symmetric M^-1/2 K M^-1/2 (M is diagonal).
        let r = mass.map(|x| 1.0 / x.sqrt());
        let s = DMatrix::from_fn(n, n, |i, j| r[i] * stiffness[(i, j)] * r[j]);
        let eig = SymmetricEigen::new(s);
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
        let omega: Vec<f64> = order
            .iter()
            .map(|&j| eig.eigenvalues[j].max(0.0).sqrt())
            .collect();
        let damping_matrix = match damping {
            Damping::Modal { zeta } => {
                // M Phi = M^1/2 Y with Phi = M^-1/2 Y: C = M^1/2 Y D Y^T M^1/2
                let sq = mass.map(f64::sqrt);
                let mut c = DMatrix::zeros(n, n);
                for (jj, &j) in order.iter().enumerate() {
                    let y = eig.eigenvectors.column(j);
                    let d = 2.0 * zeta * omega[jj];
                    for p in 0..n {
                        for q in 0..n {
                            c[(p, q)] += d * sq[p] * y[p] * y[q] * sq[q];
                        }
                    }
                }
                c
            }
            Damping::Rayleigh { alpha, beta } => {
                DMatrix::from_diagonal(&mass) * alpha + &stiffness * beta
            }
        };
        let mut a = DMatrix::zeros(2 * n, 2 * n);
        let mut b = DMatrix::zeros(2 * n, n + 1);
        for i in 0..n {
            a[(i, n + i)] = 1.0;
            for j in 0..n {
                a[(n + i, j)] = -stiffness[(i, j)] / m[i];
                a[(n + i, n + j)] = -damping_matrix[(i, j)] / m[i];
            }
            b[(n + i, 0)] = -1.0;
            b[(n + i, 1 + i)] = 1.0 / m[i];
        }
        Ok(Frame {
            n,
            mass,
            stiffness,
            damping: damping_matrix,
            omega,
            a,
            b,
        })
    }

    /// Number of storeys (floors).
    pub fn n(&self) -> usize {
        self.n
    }

    /// Natural circular frequencies, rad/s, ascending.
    pub fn omega(&self) -> &[f64] {
        &self.omega
    }

    /// Natural periods, s, descending (the fundamental first).
    pub fn periods(&self) -> Vec<f64> {
        self.omega
            .iter()
            .map(|w| 2.0 * std::f64::consts::PI / w)
            .collect()
    }

    pub fn stiffness_matrix(&self) -> &DMatrix<f64> {
        &self.stiffness
    }

    pub fn damping_matrix(&self) -> &DMatrix<f64> {
        &self.damping
    }

    /// `(Fx - C x1 - K x0)[i] / m[i]`: with `x0 = u`, `x1 = u'` the absolute
    /// acceleration.
    fn net(&self, fx: &[f64], x0: &[f64], x1: &[f64]) -> [f64; MAX_STOREYS] {
        let mut out = [0.0; MAX_STOREYS];
        for i in 0..self.n {
            let mut f = fx[i];
            for j in 0..self.n {
                f -= self.damping[(i, j)] * x1[j] + self.stiffness[(i, j)] * x0[j];
            }
            out[i] = f / self.mass[i];
        }
        out
    }

    /// Absolute floor accelerations, m/s2.
    pub fn absolute_acceleration(&self, s: &State, load: &Load) -> [f64; MAX_STOREYS] {
        self.net(&load.fx, &s.u, &s.v)
    }

    /// Storey drifts `u[i] - u[i-1]` (m), `u[0] = 0` the ground.
    pub fn drifts(&self, u: &[f64; MAX_STOREYS]) -> [f64; MAX_STOREYS] {
        let mut d = [0.0; MAX_STOREYS];
        for i in 0..self.n {
            d[i] = u[i] - if i > 0 { u[i - 1] } else { 0.0 };
        }
        d
    }

    /// First and second time derivatives of `u`, `v` and `a` at `s`, the
    /// loads being `load + rate (t - s.t)`.
    pub fn rates(&self, s: &State, load: &Load, rate: &Load) -> Rates {
        let n = self.n;
        let a = self.absolute_acceleration(s, load);
        let mut ud2 = [0.0; MAX_STOREYS];
        for i in 0..n {
            ud2[i] = a[i] - load.ag;
        }
        let da = self.net(&rate.fx, &s.v, &ud2);
        let mut ud3 = [0.0; MAX_STOREYS];
        for i in 0..n {
            ud3[i] = da[i] - rate.ag;
        }
        let zero = [0.0; MAX_STOREYS];
        let d2a = self.net(&zero, &ud2, &ud3);
        Rates {
            u: [s.v, ud2],
            v: [ud2, ud3],
            a: [da, d2a],
        }
    }

    /// The exact step of length `h` (s) of this frame.
    pub fn propagator(&self, h: f64) -> Propagator {
        let n2 = 2 * self.n;
        let p = self.n + 1;
        let size = n2 + 2 * p;
        let mut z = DMatrix::zeros(size, size);
        z.view_mut((0, 0), (n2, n2)).copy_from(&(&self.a * h));
        z.view_mut((0, n2), (n2, p)).copy_from(&(&self.b * h));
        for j in 0..p {
            z[(n2 + j, n2 + p + j)] = h;
        }
        let e = z.exp();
        Propagator {
            h,
            n: self.n,
            phi: e.view((0, 0), (n2, n2)).into_owned(),
            gamma0: e.view((0, n2), (n2, p)).into_owned(),
            gamma1: e.view((0, n2 + p), (n2, p)).into_owned(),
        }
    }
}

/// The tridiagonal stiffness matrix of storeys `k` (storey i between
/// floors i-1 and i, the ground below floor 1).
pub fn stiffness_matrix(k: &[f64]) -> DMatrix<f64> {
    let n = k.len();
    let mut s = DMatrix::zeros(n, n);
    for i in 0..n {
        s[(i, i)] += k[i];
        if i > 0 {
            s[(i - 1, i - 1)] += k[i];
            s[(i - 1, i)] -= k[i];
            s[(i, i - 1)] -= k[i];
        }
    }
    s
}

/// The exact map over one step of a fixed length: `x(h) = Phi x(0) +
/// Gamma0 w0 + Gamma1 w1` for the inputs `w0 + s w1`.
#[derive(Clone, Debug)]
pub struct Propagator {
    h: f64,
    n: usize,
    phi: DMatrix<f64>,
    gamma0: DMatrix<f64>,
    gamma1: DMatrix<f64>,
}

fn input_vector(n: usize, l: &Load) -> DVector<f64> {
    DVector::from_fn(n + 1, |i, _| if i == 0 { l.ag } else { l.fx[i - 1] })
}

impl Propagator {
    /// The step length, s.
    pub fn h(&self) -> f64 {
        self.h
    }

    /// Advances `s` by h under the loads `load + rate (t - s.t)`.
    pub fn step(&self, s: &mut State, load: &Load, rate: &Load) {
        let n = self.n;
        let x = DVector::from_fn(2 * n, |i, _| if i < n { s.u[i] } else { s.v[i - n] });
        let y = &self.phi * x
            + &self.gamma0 * input_vector(n, load)
            + &self.gamma1 * input_vector(n, rate);
        for i in 0..n {
            s.u[i] = y[i];
            s.v[i] = y[n + i];
        }
        s.t += self.h;
    }
}
