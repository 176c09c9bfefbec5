//! The exact step against independent solutions: the damped oscillator in
//! closed form, modal superposition with modes from a hand-written Jacobi
//! rotation, energy conservation, a fine Runge-Kutta integration and the
//! static storey shears.

// The references index matrices as the textbook formulas do.
#![allow(clippy::needless_range_loop)]

use shear_frame::{Damping, Frame, Load, State, MAX_STOREYS};

/// Runs `steps` exact steps of length h from `s` under constant-rate loads
/// that start at `load` (the loads advance along `rate` across steps).
fn run(frame: &Frame, s: &mut State, h: f64, steps: usize, load: Load, rate: Load) {
    let p = frame.propagator(h);
    let mut l = load;
    for _ in 0..steps {
        p.step(s, &l, &rate);
        l.ag += rate.ag * h;
        for i in 0..MAX_STOREYS {
            l.fx[i] += rate.fx[i] * h;
        }
    }
}

fn ground(ag: f64) -> Load {
    Load { ag, ..Load::ZERO }
}

/// Damped SDOF u'' + 2 zeta w u' + w^2 u = -(a0 + r t) from rest, in closed form.
fn sdof(w: f64, zeta: f64, a0: f64, r: f64, t: f64) -> (f64, f64) {
    // particular solution p0 + p1 t
    let p1 = -r / (w * w);
    let p0 = -(a0 + 2.0 * zeta * w * p1) / (w * w);
    let wd = w * (1.0 - zeta * zeta).sqrt();
    let c1 = -p0;
    let c2 = (-p1 + zeta * w * c1) / wd;
    let e = (-zeta * w * t).exp();
    let (sn, cs) = (wd * t).sin_cos();
    let u = e * (c1 * cs + c2 * sn) + p0 + p1 * t;
    let v = e * ((-zeta * w * c1 + wd * c2) * cs + (-zeta * w * c2 - wd * c1) * sn) + p1;
    (u, v)
}

#[test]
fn one_storey_step_and_ramp_of_ground_acceleration_match_the_closed_form() {
    let (m, k, zeta): (f64, f64, f64) = (2.0e5, 8.0e7, 0.05);
    let w = (k / m).sqrt();
    let frame = Frame::new(&[m], &[k], Damping::Modal { zeta }).unwrap();
    assert!((frame.omega()[0] - w).abs() < 1e-12 * w);
    for (a0, r) in [(1.5, 0.0), (0.0, 2.0), (-0.7, 3.0)] {
        let mut s = State::at_rest(0.0);
        let h = 0.01;
        let mut worst: f64 = 0.0;
        for j in 1..=300 {
            run(
                &frame,
                &mut s,
                h,
                1,
                ground(a0 + r * (j - 1) as f64 * h),
                ground(r),
            );
            let t = j as f64 * h;
            let (u, v) = sdof(w, zeta, a0, r, t);
            let scale = (a0.abs() + r * t) / (w * w);
            worst = worst.max((s.u[0] - u).abs() / scale);
            worst = worst.max((s.v[0] - v).abs() / (scale * w));
            // the absolute acceleration is u'' + ag
            let a = frame.absolute_acceleration(&s, &ground(a0 + r * t))[0];
            let ud2 = -2.0 * zeta * w * v - w * w * u - (a0 + r * t);
            assert!((a - (ud2 + a0 + r * t)).abs() < 1e-9 * scale * w * w);
        }
        eprintln!("SDOF a0 = {a0}, r = {r}: relative error {worst:e}");
        assert!(
            worst < 1e-11,
            "a0 = {a0}, r = {r}: relative error {worst:e}"
        );
    }
}

/// Eigenvalues and eigenvectors (columns) of a symmetric matrix by cyclic
/// Jacobi rotations.
fn jacobi(mut a: Vec<Vec<f64>>) -> (Vec<f64>, Vec<Vec<f64>>) {
    let n = a.len();
    let mut v = vec![vec![0.0; n]; n];
    for (i, row) in v.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for _sweep in 0..100 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum();
        if off < 1e-30 {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                if a[p][q] == 0.0 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..n {
                    let (akp, akq) = (a[k][p], a[k][q]);
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for k in 0..n {
                    let (apk, aqk) = (a[p][k], a[q][k]);
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for row in v.iter_mut() {
                    let (vp, vq) = (row[p], row[q]);
                    row[p] = c * vp - s * vq;
                    row[q] = s * vp + c * vq;
                }
            }
        }
    }
    ((0..n).map(|i| a[i][i]).collect(), v)
}

const M5: [f64; 5] = [3.0e5, 2.8e5, 2.6e5, 2.5e5, 1.5e5];
const K5: [f64; 5] = [4.0e8, 3.5e8, 3.0e8, 2.5e8, 1.5e8];

#[test]
fn five_storey_free_vibration_is_the_modal_superposition() {
    let n = 5;
    let zeta = 0.03;
    let frame = Frame::new(&M5, &K5, Damping::Modal { zeta }).unwrap();
    // M^-1/2 K M^-1/2 with K assembled by hand
    let mut kk = vec![vec![0.0; n]; n];
    for i in 0..n {
        kk[i][i] += K5[i];
        if i + 1 < n {
            kk[i][i] += K5[i + 1];
            kk[i][i + 1] = -K5[i + 1];
            kk[i + 1][i] = -K5[i + 1];
        }
    }
    let s: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| kk[i][j] / (M5[i] * M5[j]).sqrt()).collect())
        .collect();
    let (lambda, y) = jacobi(s);
    let w: Vec<f64> = lambda.iter().map(|l| l.sqrt()).collect();
    let mut ws = w.clone();
    ws.sort_by(f64::total_cmp);
    for (a, b) in ws.iter().zip(frame.omega()) {
        assert!((a - b).abs() < 1e-12 * b, "omega {a} vs {b}");
    }
    // mass-normalised modes phi_j = M^-1/2 y_j
    let phi = |i: usize, j: usize| y[i][j] / M5[i].sqrt();
    let u0 = [0.01, 0.02, -0.01, 0.03, 0.05];
    let v0 = [0.1, -0.2, 0.0, 0.3, -0.1];
    let mut s0 = State::at_rest(0.0);
    s0.u[..n].copy_from_slice(&u0);
    s0.v[..n].copy_from_slice(&v0);
    // modal coordinates q_j = phi_j^T M x
    let q = |x: &[f64], j: usize| (0..n).map(|i| phi(i, j) * M5[i] * x[i]).sum::<f64>();
    let h = 0.005;
    let mut s = s0;
    let p = frame.propagator(h);
    let mut worst: f64 = 0.0;
    for step in 1..=800 {
        p.step(&mut s, &Load::ZERO, &Load::ZERO);
        let t = step as f64 * h;
        for i in 0..n {
            let mut u = 0.0;
            for (j, &wj) in w.iter().enumerate() {
                let wd = wj * (1.0 - zeta * zeta).sqrt();
                let (q0, qd0) = (q(&u0, j), q(&v0, j));
                let e = (-zeta * wj * t).exp();
                let qt = e * (q0 * (wd * t).cos() + (qd0 + zeta * wj * q0) / wd * (wd * t).sin());
                u += phi(i, j) * qt;
            }
            worst = worst.max((s.u[i] - u).abs() / 0.05);
        }
    }
    eprintln!("5 storeys, modal superposition: relative error {worst:e}");
    assert!(worst < 1e-10, "relative error {worst:e}");
}

fn energy(s: &State, m: &[f64], k: &[f64]) -> f64 {
    let mut e = 0.0;
    for i in 0..m.len() {
        let drift = s.u[i] - if i > 0 { s.u[i - 1] } else { 0.0 };
        e += 0.5 * m[i] * s.v[i] * s.v[i] + 0.5 * k[i] * drift * drift;
    }
    e
}

#[test]
fn without_damping_energy_minus_the_work_of_constant_forces_is_conserved() {
    let frame = Frame::new(&M5, &K5, Damping::Modal { zeta: 0.0 }).unwrap();
    let mut load = Load::ZERO;
    load.fx[1] = 2.0e5;
    load.fx[4] = -1.0e5;
    let mut s = State::at_rest(0.0);
    s.u[..5].copy_from_slice(&[0.01, 0.015, 0.02, 0.02, 0.03]);
    let total = |s: &State| energy(s, &M5, &K5) - (0..5).map(|i| load.fx[i] * s.u[i]).sum::<f64>();
    let e0 = total(&s);
    let p = frame.propagator(0.013);
    let mut worst: f64 = 0.0;
    for _ in 0..2000 {
        p.step(&mut s, &load, &Load::ZERO);
        worst = worst.max((total(&s) - e0).abs() / energy(&s, &M5, &K5).max(e0.abs()));
    }
    eprintln!("undamped energy drift over 2000 steps: {worst:e}");
    assert!(worst < 1e-11, "relative energy drift {worst:e}");
}

#[test]
fn damped_energy_decreases_by_the_dissipated_work() {
    // with Rayleigh damping: E(t) - E(0) = -int v^T C v dt (trapezoid on a fine grid)
    let frame = Frame::new(
        &M5,
        &K5,
        Damping::Rayleigh {
            alpha: 0.4,
            beta: 0.002,
        },
    )
    .unwrap();
    let c = frame.damping_matrix().clone();
    let mut s = State::at_rest(0.0);
    s.v[..5].copy_from_slice(&[0.2, -0.1, 0.3, 0.1, -0.2]);
    let e0 = energy(&s, &M5, &K5);
    let diss = |s: &State| {
        let mut d = 0.0;
        for i in 0..5 {
            for j in 0..5 {
                d += s.v[i] * c[(i, j)] * s.v[j];
            }
        }
        d
    };
    let h = 1e-5;
    let p = frame.propagator(h);
    let mut work = 0.0;
    let mut d_prev = diss(&s);
    for _ in 0..20000 {
        p.step(&mut s, &Load::ZERO, &Load::ZERO);
        let d = diss(&s);
        work += 0.5 * h * (d + d_prev);
        d_prev = d;
    }
    let e1 = energy(&s, &M5, &K5);
    assert!(e1 < 0.9 * e0);
    assert!(
        ((e0 - e1) - work).abs() < 1e-6 * e0,
        "{} vs {work}",
        e0 - e1
    );
}

/// Classical RK4 on M u'' + C u' + K u = -M ag + Fx.
fn rk4(frame: &Frame, m: &[f64], s: &mut State, h: f64, steps: usize, load: Load, rate: Load) {
    let n = m.len();
    let f = |t: f64, u: &[f64], v: &[f64]| -> (Vec<f64>, Vec<f64>) {
        let mut st = State::at_rest(t);
        st.u[..n].copy_from_slice(u);
        st.v[..n].copy_from_slice(v);
        let _ = &st;
        let k = frame.stiffness_matrix();
        let c = frame.damping_matrix();
        let ag = load.ag + rate.ag * t;
        let acc = (0..n)
            .map(|i| {
                let mut fi = load.fx[i] + rate.fx[i] * t;
                for j in 0..n {
                    fi -= k[(i, j)] * u[j] + c[(i, j)] * v[j];
                }
                fi / m[i] - ag
            })
            .collect();
        (v.to_vec(), acc)
    };
    let axpy = |x: &[f64], a: f64, y: &[f64]| -> Vec<f64> {
        x.iter().zip(y).map(|(p, q)| p + a * q).collect()
    };
    let mut u = s.u[..n].to_vec();
    let mut v = s.v[..n].to_vec();
    for j in 0..steps {
        let t = j as f64 * h;
        let (k1u, k1v) = f(t, &u, &v);
        let (k2u, k2v) = f(
            t + h / 2.0,
            &axpy(&u, h / 2.0, &k1u),
            &axpy(&v, h / 2.0, &k1v),
        );
        let (k3u, k3v) = f(
            t + h / 2.0,
            &axpy(&u, h / 2.0, &k2u),
            &axpy(&v, h / 2.0, &k2v),
        );
        let (k4u, k4v) = f(t + h, &axpy(&u, h, &k3u), &axpy(&v, h, &k3v));
        for i in 0..n {
            u[i] += h / 6.0 * (k1u[i] + 2.0 * k2u[i] + 2.0 * k3u[i] + k4u[i]);
            v[i] += h / 6.0 * (k1v[i] + 2.0 * k2v[i] + 2.0 * k3v[i] + k4v[i]);
        }
    }
    s.u[..n].copy_from_slice(&u);
    s.v[..n].copy_from_slice(&v);
}

#[test]
fn agrees_with_a_fine_runge_kutta_integration_under_ramped_loads() {
    let m = [2.0e5, 1.8e5, 1.2e5];
    let k = [2.0e8, 1.6e8, 1.0e8];
    let frame = Frame::new(
        &m,
        &k,
        Damping::Rayleigh {
            alpha: 0.3,
            beta: 0.001,
        },
    )
    .unwrap();
    let mut load = ground(0.5);
    load.fx[2] = 3.0e4;
    let mut rate = ground(-1.2);
    rate.fx[0] = 5.0e4;
    let mut exact = State::at_rest(0.0);
    run(&frame, &mut exact, 0.05, 40, load, rate);
    let mut reference = State::at_rest(0.0);
    rk4(&frame, &m, &mut reference, 1e-4, 20000, load, rate);
    let scale = reference.u[..3].iter().fold(0.0f64, |a, x| a.max(x.abs()));
    for i in 0..3 {
        assert!(
            (exact.u[i] - reference.u[i]).abs() < 1e-10 * scale,
            "u[{}]: {} vs {}",
            i + 1,
            exact.u[i],
            reference.u[i]
        );
    }
}

#[test]
fn constant_floor_forces_settle_at_the_static_storey_shears() {
    // drift of storey i = (sum of the forces on floors >= i) / k[i]
    let frame = Frame::new(&M5, &K5, Damping::Modal { zeta: 0.7 }).unwrap();
    let mut load = Load::ZERO;
    load.fx[..5].copy_from_slice(&[1.0e5, 0.0, -3.0e4, 0.0, 5.0e4]);
    let mut s = State::at_rest(0.0);
    run(&frame, &mut s, 0.5, 40, load, Load::ZERO);
    let d = frame.drifts(&s.u);
    for i in 0..5 {
        let shear: f64 = load.fx[i..5].iter().sum();
        assert!(
            (d[i] - shear / K5[i]).abs() < 1e-12 * 1e-3,
            "storey {}: {} vs {}",
            i + 1,
            d[i],
            shear / K5[i]
        );
    }
    let a = frame.absolute_acceleration(&s, &load);
    assert!(a[..5].iter().all(|x| x.abs() < 1e-9));
}

#[test]
fn bad_parameters_name_the_variable() {
    let ok = Damping::Modal { zeta: 0.05 };
    let cases: Vec<(Result<Frame, String>, &str)> = vec![
        (Frame::new(&[], &[], ok), "n = 0"),
        (Frame::new(&[1.0; 21], &[1.0; 21], ok), "n = 21"),
        (Frame::new(&[1.0, -2.0], &[1.0, 1.0], ok), "m[2] = -2"),
        (Frame::new(&[1.0, 2.0], &[1.0, 0.0], ok), "k[2] = 0"),
        (Frame::new(&[f64::NAN], &[1.0], ok), "m[1] = NaN"),
        (
            Frame::new(&[1.0], &[1.0], Damping::Modal { zeta: -0.1 }),
            "zeta = -0.1",
        ),
        (
            Frame::new(
                &[1.0],
                &[1.0],
                Damping::Rayleigh {
                    alpha: -1.0,
                    beta: 0.0,
                },
            ),
            "rayleighAlpha = -1",
        ),
    ];
    for (r, name) in cases {
        let e = r.unwrap_err();
        assert!(e.starts_with(name), "{e:?} should start with {name:?}");
    }
}

#[test]
fn rates_are_the_derivatives_of_the_exact_trajectory() {
    // central differences of the exact solution under a ramp
    let frame = Frame::new(&M5, &K5, Damping::Modal { zeta: 0.05 }).unwrap();
    let mut s = State::at_rest(0.0);
    s.u[..5].copy_from_slice(&[0.01, 0.02, 0.025, 0.03, 0.04]);
    let mut load = ground(0.8);
    load.fx[3] = 1e5;
    let mut rate = ground(2.0);
    rate.fx[3] = -3e5;
    let r = frame.rates(&s, &load, &rate);
    let h = 2e-5;
    // the exact map also runs backwards (a negative step)
    let at = |dt: f64| {
        let mut x = s;
        if dt != 0.0 {
            frame.propagator(dt).step(&mut x, &load, &rate);
        }
        let mut l = load;
        l.ag += rate.ag * dt;
        for i in 0..5 {
            l.fx[i] += rate.fx[i] * dt;
        }
        (x, frame.absolute_acceleration(&x, &l))
    };
    let (xp, ap) = at(h);
    let (xm, am) = at(-h);
    let (_, a0) = at(0.0);
    for i in 0..5 {
        let du = (xp.u[i] - xm.u[i]) / (2.0 * h);
        let dv = (xp.v[i] - xm.v[i]) / (2.0 * h);
        let da = (ap[i] - am[i]) / (2.0 * h);
        let d2a = (ap[i] - 2.0 * a0[i] + am[i]) / (h * h);
        let d2u = (xp.u[i] - 2.0 * s.u[i] + xm.u[i]) / (h * h);
        // The finite difference `fd` against the derivative `exact`, relative to 1 + |fd|.
        let near = |fd: f64, exact: f64, tol: f64, what: &str| {
            assert!(
                (fd - exact).abs() < tol * (1.0 + fd.abs()),
                "{what} {fd} {exact}"
            );
        };
        near(du, r.u[0][i], 1e-6, "u'");
        near(d2u, r.u[1][i], 1e-4, "u''");
        near(dv, r.v[0][i], 1e-6, "v'");
        near(da, r.a[0][i], 1e-5, "a'");
        near(d2a, r.a[1][i], 1e-3, "a''");
    }
}
