//! The impact when the base returns to the bed (docs/model.md §10.3).
//!
//! The base strikes at the rim point `P+` toward which the tilt is moving;
//! the impulse acts there and the body leaves rolling about it (Housner's
//! assumptions, in space). The angular momentum about `P+` is conserved:
//! `J+ omega+ = IG omega- + m r+ x (omega- x r-)`, with `r± = G - P±` at
//! upright. In a plane this is Housner's `eta = 1 - 2 m R² / IO` exactly;
//! with `restitution = given` the rocking part of `omega+` (about
//! `k = z x d+`) is `eta` times that of `omega-`, so that the planar limit
//! is today's rule, and its other parts are as above.

use nalgebra::{Matrix3, Vector3};

use super::Spatial;
use crate::model::Restitution;

/// The outcome of one impact.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Impact {
    /// Angular velocity after, rad/s.
    pub omega: Vector3<f64>,
    /// Direction of the new contact (unit, horizontal).
    pub pivot: [f64; 2],
}

/// The impact of a body arriving upright with `omega` (rad/s), in contact
/// in the direction `old` (unit). The new contact is where `omega+` tilts
/// the body, which depends on `omega+` when the body spins: a fixed point,
/// found in a few iterations (at once without spin).
pub(crate) fn impact(body: &Spatial, omega: Vector3<f64>, old: [f64; 2]) -> Impact {
    let mut pivot = tilt_direction(&omega).unwrap_or([-old[0], -old[1]]);
    let mut after = omega;
    for _ in 0..16 {
        after = omega_after(body, &omega, old, pivot);
        let next = tilt_direction(&after).unwrap_or(pivot);
        let moved = (next[0] - pivot[0]).hypot(next[1] - pivot[1]);
        pivot = next;
        if moved <= 4.0 * f64::EPSILON {
            break;
        }
    }
    Impact {
        omega: after,
        pivot,
    }
}

/// The horizontal direction the axis moves in under `omega` at upright,
/// `(omega x z)_h / |.|`, if it moves.
fn tilt_direction(omega: &Vector3<f64>) -> Option<[f64; 2]> {
    let (x, y) = (omega.y, -omega.x);
    let n = x.hypot(y);
    (n > 0.0).then(|| [x / n, y / n])
}

/// `G - P` at upright for the contact in the direction `d`, m.
fn lever(body: &Spatial, d: [f64; 2]) -> Vector3<f64> {
    Vector3::new(-body.radius * d[0], -body.radius * d[1], body.model.body.hg)
}

/// Inertia about the centre of mass at upright, kg m².
fn inertia_upright(body: &Spatial) -> Matrix3<f64> {
    let a = body.model.body.ic;
    Matrix3::from_diagonal(&Vector3::new(a, a, body.c_axial))
}

/// Inertia about the contact point at `G - P = r`, kg m².
pub(crate) fn inertia_about(ig: &Matrix3<f64>, m: f64, r: &Vector3<f64>) -> Matrix3<f64> {
    ig + m * (Matrix3::identity() * r.norm_squared() - r * r.transpose())
}

fn omega_after(
    body: &Spatial,
    omega: &Vector3<f64>,
    old: [f64; 2],
    pivot: [f64; 2],
) -> Vector3<f64> {
    let m = body.mass();
    let ig = inertia_upright(body);
    let (r_old, r_new) = (lever(body, old), lever(body, pivot));
    let h = ig * omega + m * r_new.cross(&omega.cross(&r_old));
    let j = inertia_about(&ig, m, &r_new);
    let mut after = match j.cholesky() {
        Some(ch) => ch.solve(&h),
        None => Vector3::repeat(f64::NAN),
    };
    if body.restitution == Restitution::Given {
        let k = Vector3::new(-pivot[1], pivot[0], 0.0);
        after += (body.model.eta * omega.dot(&k) - after.dot(&k)) * k;
    }
    after
}

/// Kinetic energy `omega^T J omega / 2` of a body at upright rolling about
/// the contact in the direction `d`, J.
#[cfg(test)]
fn kinetic_upright(body: &Spatial, omega: &Vector3<f64>, d: [f64; 2]) -> f64 {
    let j = inertia_about(&inertia_upright(body), body.mass(), &lever(body, d));
    0.5 * omega.dot(&(j * omega))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{LawKind, MassKind, Params, ShapeKind};

    fn drum(restitution: Restitution) -> Spatial {
        let p = Params {
            shape: ShapeKind::HollowCircle,
            ro: 0.6,
            ri: 0.4,
            mass_model: MassKind::Prism,
            h: 4.0,
            interface: LawKind::Rigid,
            restitution,
            eta: 0.7,
            ..Params::default()
        };
        Spatial::new(&p, None, 1e-10).unwrap()
    }

    /// Arriving upright in the direction `-old` with a tilt rate `w` and a spin `s`.
    fn arriving(old: [f64; 2], w: f64, s: f64) -> Vector3<f64> {
        // the tilt moves toward -old: omega_h = w (z x -old)
        Vector3::new(w * old[1], -w * old[0], s)
    }

    #[test]
    fn in_a_plane_the_law_is_housners_or_the_given_eta() {
        let old = [0.6, 0.8];
        for (restitution, ratio) in [
            (
                Restitution::Housner,
                drum(Restitution::Housner).model.body.eta_housner(),
            ),
            (Restitution::Given, 0.7),
        ] {
            let body = drum(restitution);
            let out = impact(&body, arriving(old, 0.4, 0.0), old);
            let expected = ratio * arriving(old, 0.4, 0.0);
            assert!((out.omega - expected).norm() <= 1e-15, "{:?}", out.omega);
            assert!((out.pivot[0] + old[0]).abs() + (out.pivot[1] + old[1]).abs() <= 1e-15);
        }
    }

    #[test]
    fn with_spin_the_impact_loses_energy_and_leaves_on_its_new_contact() {
        let body = drum(Restitution::Housner);
        let old = [1.0, 0.0];
        for s in [-2.0, -0.3, 0.1, 1.5] {
            let before = arriving(old, 0.5, s);
            let out = impact(&body, before, old);
            let e0 = kinetic_upright(&body, &before, old);
            let e1 = kinetic_upright(&body, &out.omega, out.pivot);
            assert!(e1 < e0, "spin {s}: {e1} >= {e0}");
            // the body tilts onto the contact the law assumed
            let dir = tilt_direction(&out.omega).unwrap();
            assert!((dir[0] - out.pivot[0]).hypot(dir[1] - out.pivot[1]) <= 1e-14);
            // angular momentum about the new contact, from the velocity
            // field before (about the old contact) and after (about the new)
            let m = body.mass();
            let ig = inertia_upright(&body);
            let (r0, r1) = (lever(&body, old), lever(&body, out.pivot));
            let h_before = ig * before + m * r1.cross(&before.cross(&r0));
            let h_after = ig * out.omega + m * r1.cross(&out.omega.cross(&r1));
            assert!((h_before - h_after).norm() <= 1e-12 * h_before.norm());
        }
    }
}
