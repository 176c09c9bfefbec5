//! Embedded explicit Runge-Kutta pairs for the 2-dimensional system
//! `y = (theta, omega)`, `y' = (omega, theta'')`: Dormand-Prince 5(4) and
//! Dormand-Prince 8(5,3) ("DOP853", Hairer, Nørsett & Wanner, *Solving ODEs I*,
//! §II.5 and §II.10). Coefficients as in Hairer's `dop853.f` (also used by
//! SciPy's `solve_ivp`). Nothing allocates: stages live on the stack.
// The coefficients are kept with all the digits of the published tables.
#![allow(clippy::excessive_precision)]

use super::eom::Eom;

/// Error weights. The error of a step is measured relative to the size of
/// the motion it is part of, so that small rocking (late in a chattering
/// sequence, or on a stiff interface) keeps the same relative accuracy as
/// large rocking:
///
/// - `sc_theta = atol_theta + rtol max(A(y0), A(y1))`, `A = |theta| + omega² / (2 g_eff)`,
///   the amplitude the body would reach against the deceleration `g_eff`;
/// - `sc_omega = atol_omega + rtol max(V(y0), V(y1))`, `V = sqrt(omega² + 2 g_eff |theta|)`,
///   the velocity it would have at `theta = 0`;
///
/// with `g_eff = W b / IO` the angular deceleration of the rigid body at
/// `theta = 0`. `A, V` are exact invariants of the rigid motion for small
/// rotations (a parabola) and scales otherwise.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tol {
    pub rtol: f64,
    pub atol_theta: f64,
    pub atol_omega: f64,
    /// `2 g_eff`, rad/s².
    pub two_g: f64,
}

impl Tol {
    #[inline(always)]
    pub fn amp(&self, y: [f64; 2]) -> f64 {
        y[0].abs() + y[1] * y[1] / self.two_g
    }

    #[inline(always)]
    fn vel(&self, y: [f64; 2]) -> f64 {
        (y[1] * y[1] + self.two_g * y[0].abs()).sqrt()
    }

    #[inline(always)]
    pub fn scales(&self, y0: [f64; 2], y1: [f64; 2]) -> [f64; 2] {
        [
            self.atol_theta + self.rtol * self.amp(y0).max(self.amp(y1)),
            self.atol_omega + self.rtol * self.vel(y0).max(self.vel(y1)),
        ]
    }
}

/// The point a step starts from, and the equation it follows.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Start<'a> {
    pub eom: &'a Eom<'a>,
    /// Time, s.
    pub t: f64,
    /// `(theta, omega)`, rad and rad/s.
    pub y0: [f64; 2],
    /// `theta''` at `(t, y0)`, rad/s².
    pub a0: f64,
    /// The toe the body rocks about (see `eom::side_of`).
    pub side: f64,
}

impl Start<'_> {
    /// `theta''` at `(t, y)` on the step's side, rad/s² (`hint`: the warm
    /// start of the contact solve, see `Eom::accel`).
    #[inline(always)]
    pub fn accel(&self, t: f64, y: [f64; 2], hint: &mut f64) -> f64 {
        self.eom.accel(t, y[0], y[1], self.side, hint)
    }
}

/// One attempted step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StepOut {
    /// `(theta, omega)` at the end of the step.
    pub y: [f64; 2],
    /// `theta''` at the end of the step (first stage of the next one).
    pub accel: f64,
    /// Scaled error estimate: the step is acceptable when `err <= 1`.
    pub err: f64,
    /// Estimate of the spectral radius of the Jacobian, 1/s: for the
    /// explicit pairs `sqrt(|Δtheta'' / Δtheta|)` between the two stages at
    /// `c = 1` (Hairer's stiffness detection), for RODAS from its Jacobian.
    pub rho: f64,
}

/// `sqrt(|Δa / Δtheta|)` between two states at the same time.
#[inline(always)]
fn rho(th_a: f64, a_a: f64, th_b: f64, a_b: f64) -> f64 {
    let d = th_a - th_b;
    if d != 0.0 {
        ((a_a - a_b) / d).abs().sqrt()
    } else {
        0.0
    }
}

/// A pair of embedded formulas.
pub(crate) trait Pair {
    /// Order of the propagated solution.
    const ORDER: u32;
    /// `-1 / (q + 1)` with `q` the order the error estimate is
    /// asymptotic to (the step-size controller's exponent).
    const ERR_EXP: f64;
    /// Right-hand-side evaluations of an accepted step (FSAL counted once).
    const EVALS: u32;
    /// A step of `h` from `s`; `hint` carries the contact solve's warm
    /// start through the stages.
    fn step(s: &Start, h: f64, hint: &mut f64, tol: &Tol) -> StepOut;
}

/// The stages of an explicit method of `S` stages (first same as last):
/// `kw[j]` is stage `j`'s `omega` (= `theta'`), `ka[j]` its `theta''`.
struct Stages<const S: usize> {
    kw: [f64; S],
    ka: [f64; S],
    /// `(theta, omega)` at the end of the step, and its `theta''`.
    y1: [f64; 2],
    a1: f64,
    /// `theta` of the last stage, which is at `c = 1` too (for `rho`).
    th_last: f64,
}

/// All stages of a step of `h` of the tableau `(c, a, b)` from `s`, and
/// `f(y1)` at its end.
#[inline(always)]
fn stages<const S: usize>(
    s: &Start,
    h: f64,
    hint: &mut f64,
    (c, a, b): (&[f64; S], &[[f64; S]], &[f64; S]),
) -> Stages<S> {
    let mut st = Stages {
        kw: [0.0; S],
        ka: [0.0; S],
        y1: s.y0,
        a1: s.a0,
        th_last: s.y0[0],
    };
    st.kw[0] = s.y0[1];
    st.ka[0] = s.a0;
    for i in 1..S {
        let y = st.combine(s.y0, h, &a[i], i);
        st.kw[i] = y[1];
        st.ka[i] = s.accel(s.t + c[i] * h, y, hint);
        st.th_last = y[0];
    }
    st.y1 = st.combine(s.y0, h, b, S);
    st.a1 = s.accel(s.t + h, st.y1, hint);
    st
}

impl<const S: usize> Stages<S> {
    /// `y0 + h sum_j row_j k_j` over the first `i` stages: the state at
    /// which stage `i` is evaluated.
    #[inline(always)]
    fn combine(&self, y0: [f64; 2], h: f64, row: &[f64; S], i: usize) -> [f64; 2] {
        let mut sw = 0.0;
        let mut sa = 0.0;
        for ((r, w), a) in row[..i].iter().zip(&self.kw).zip(&self.ka) {
            sw += r * w;
            sa += r * a;
        }
        [y0[0] + h * sw, y0[1] + h * sa]
    }

    /// `init + sum_j e_j (kw_j, ka_j)`, summed in stage order: an error
    /// estimate's combination of the stages.
    #[inline(always)]
    fn weighted(&self, init: [f64; 2], e: &[f64; S]) -> [f64; 2] {
        let [mut w, mut a] = init;
        for ((e, kw), ka) in e.iter().zip(&self.kw).zip(&self.ka) {
            w += e * kw;
            a += e * ka;
        }
        [w, a]
    }

    /// The step's result with the scaled error `err`; `rho` from the last
    /// stage and the end, both at `c = 1` (Hairer's stiffness detection).
    fn out(&self, err: f64) -> StepOut {
        StepOut {
            y: self.y1,
            accel: self.a1,
            err,
            rho: rho(self.y1[0], self.a1, self.th_last, self.ka[S - 1]),
        }
    }
}

/// Dormand-Prince 5(4), 7 stages, first same as last.
pub(crate) struct Dp5;

const DP5_C: [f64; 6] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0];
const DP5_A: [[f64; 6]; 6] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
];
const DP5_B: [f64; 6] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
];
/// `b - b_hat` of the embedded 4th-order formula on the 6 stages...
const DP5_E: [f64; 6] = [
    -71.0 / 57600.0,
    0.0,
    71.0 / 16695.0,
    -71.0 / 1920.0,
    17253.0 / 339200.0,
    -22.0 / 525.0,
];
/// ... and on `f(y1)`, the 7th stage (first same as last).
const DP5_E_END: f64 = 1.0 / 40.0;

impl Pair for Dp5 {
    const ORDER: u32 = 5;
    const ERR_EXP: f64 = -1.0 / 5.0;
    const EVALS: u32 = 6;

    #[inline]
    fn step(start: &Start, h: f64, hint: &mut f64, tol: &Tol) -> StepOut {
        let s = stages(start, h, hint, (&DP5_C, &DP5_A, &DP5_B));
        let e_end = [DP5_E_END * s.y1[1], DP5_E_END * s.a1];
        let [ew, ea] = s.weighted(e_end, &DP5_E);
        let sc = tol.scales(start.y0, s.y1);
        let e0 = h * ew / sc[0];
        let e1 = h * ea / sc[1];
        s.out((0.5 * (e0 * e0 + e1 * e1)).sqrt())
    }
}

/// Dormand-Prince 8(5,3): 12 stages plus `f(y1)`, error estimate from the
/// embedded 5th- and 3rd-order formulas as in Hairer's `dop853`.
pub(crate) struct Dop853;

pub(crate) const N12: usize = 12;

pub(crate) const DOP_C: [f64; N12] = [
    0.0,
    0.526001519587677318785587544488e-01,
    0.789002279381515978178381316732e-01,
    0.118350341907227396726757197510,
    0.281649658092772603273242802490,
    0.333333333333333333333333333333,
    0.25,
    0.307692307692307692307692307692,
    0.651282051282051282051282051282,
    0.6,
    0.857142857142857142857142857142,
    1.0,
];

const fn dop_a() -> [[f64; N12]; N12 + 1] {
    let mut a = [[0.0; N12]; N12 + 1];
    a[1][0] = 5.26001519587677318785587544488e-2;

    a[2][0] = 1.97250569845378994544595329183e-2;
    a[2][1] = 5.91751709536136983633785987549e-2;

    a[3][0] = 2.95875854768068491816892993775e-2;
    a[3][2] = 8.87627564304205475450678981324e-2;

    a[4][0] = 2.41365134159266685502369798665e-1;
    a[4][2] = -8.84549479328286085344864962717e-1;
    a[4][3] = 9.24834003261792003115737966543e-1;

    a[5][0] = 3.7037037037037037037037037037e-2;
    a[5][3] = 1.70828608729473871279604482173e-1;
    a[5][4] = 1.25467687566822425016691814123e-1;

    a[6][0] = 3.7109375e-2;
    a[6][3] = 1.70252211019544039314978060272e-1;
    a[6][4] = 6.02165389804559606850219397283e-2;
    a[6][5] = -1.7578125e-2;

    a[7][0] = 3.70920001185047927108779319836e-2;
    a[7][3] = 1.70383925712239993810214054705e-1;
    a[7][4] = 1.07262030446373284651809199168e-1;
    a[7][5] = -1.53194377486244017527936158236e-2;
    a[7][6] = 8.27378916381402288758473766002e-3;

    a[8][0] = 6.24110958716075717114429577812e-1;
    a[8][3] = -3.36089262944694129406857109825;
    a[8][4] = -8.68219346841726006818189891453e-1;
    a[8][5] = 2.75920996994467083049415600797e1;
    a[8][6] = 2.01540675504778934086186788979e1;
    a[8][7] = -4.34898841810699588477366255144e1;

    a[9][0] = 4.77662536438264365890433908527e-1;
    a[9][3] = -2.48811461997166764192642586468;
    a[9][4] = -5.90290826836842996371446475743e-1;
    a[9][5] = 2.12300514481811942347288949897e1;
    a[9][6] = 1.52792336328824235832596922938e1;
    a[9][7] = -3.32882109689848629194453265587e1;
    a[9][8] = -2.03312017085086261358222928593e-2;

    a[10][0] = -9.3714243008598732571704021658e-1;
    a[10][3] = 5.18637242884406370830023853209;
    a[10][4] = 1.09143734899672957818500254654;
    a[10][5] = -8.14978701074692612513997267357;
    a[10][6] = -1.85200656599969598641566180701e1;
    a[10][7] = 2.27394870993505042818970056734e1;
    a[10][8] = 2.49360555267965238987089396762;
    a[10][9] = -3.0467644718982195003823669022;

    a[11][0] = 2.27331014751653820792359768449;
    a[11][3] = -1.05344954667372501984066689879e1;
    a[11][4] = -2.00087205822486249909675718444;
    a[11][5] = -1.79589318631187989172765950534e1;
    a[11][6] = 2.79488845294199600508499808837e1;
    a[11][7] = -2.85899827713502369474065508674;
    a[11][8] = -8.87285693353062954433549289258;
    a[11][9] = 1.23605671757943030647266201528e1;
    a[11][10] = 6.43392746015763530355970484046e-1;

    // the weights b of the 8th-order solution
    a[12][0] = 5.42937341165687622380535766363e-2;
    a[12][5] = 4.45031289275240888144113950566;
    a[12][6] = 1.89151789931450038304281599044;
    a[12][7] = -5.8012039600105847814672114227;
    a[12][8] = 3.1116436695781989440891606237e-1;
    a[12][9] = -1.52160949662516078556178806805e-1;
    a[12][10] = 2.01365400804030348374776537501e-1;
    a[12][11] = 4.47106157277725905176885569043e-2;
    a
}

pub(crate) const DOP_A: [[f64; N12]; N12 + 1] = dop_a();

const fn dop_e3() -> [f64; N12] {
    let mut e = DOP_A[N12];
    e[0] -= 0.244094488188976377952755905512;
    e[8] -= 0.733846688281611857341361741547;
    e[11] -= 0.220588235294117647058823529412e-1;
    e
}

pub(crate) const DOP_E3: [f64; N12] = dop_e3();
pub(crate) const DOP_E5: [f64; N12] = [
    0.1312004499419488073250102996e-1,
    0.0,
    0.0,
    0.0,
    0.0,
    -0.1225156446376204440720569753e+1,
    -0.4957589496572501915214079952,
    0.1664377182454986536961530415e+1,
    -0.3503288487499736816886487290,
    0.3341791187130174790297318841,
    0.8192320648511571246570742613e-1,
    -0.2235530786388629525884427845e-1,
];

impl Pair for Dop853 {
    const ORDER: u32 = 8;
    const ERR_EXP: f64 = -1.0 / 8.0;
    const EVALS: u32 = 12;

    #[inline]
    fn step(start: &Start, h: f64, hint: &mut f64, tol: &Tol) -> StepOut {
        let tableau = (&DOP_C, &DOP_A[..N12], &DOP_A[N12]);
        let s = stages(start, h, hint, tableau);
        let [e5w, e5a] = s.weighted([0.0; 2], &DOP_E5);
        let [e3w, e3a] = s.weighted([0.0; 2], &DOP_E3);
        let sc = tol.scales(start.y0, s.y1);
        let (e5w, e5a, e3w, e3a) = (e5w / sc[0], e5a / sc[1], e3w / sc[0], e3a / sc[1]);
        let n5 = e5w * e5w + e5a * e5a;
        let n3 = e3w * e3w + e3a * e3a;
        let err = if n5 == 0.0 && n3 == 0.0 {
            0.0
        } else {
            h.abs() * n5 / ((n5 + 0.01 * n3) * 2.0).sqrt()
        };
        s.out(err)
    }
}
