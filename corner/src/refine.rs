//! Continuous refinement of the grid optimum by Nelder-Mead (argmin), the paper's optimiser.
//!
//! The constraints enter as a penalty: an infeasible point costs more than any feasible one
//! (a constant above every multiplier plus the violation), so the simplex stays inside. It is a
//! local method; started from the exact grid optimum it can only improve it, and the better of
//! the two is returned.

use argmin::core::{CostFunction, Error, Executor};
use argmin::solver::neldermead::NelderMead;

use crate::{CornerModel, Evaluation, Geometry};

struct Problem<'a> {
    model: &'a CornerModel,
    alpha: f64,
}

fn geometry(p: &[f64]) -> Geometry {
    Geometry {
        x1: p[0],
        x2: p[1],
        x3: p[2],
        y1: p[3],
        y2: p[4],
        y3: p[5],
        z1: p[6],
    }
}

/// Sum of the constraint violations (m); zero when admissible.
fn violation(model: &CornerModel, x: &Geometry) -> f64 {
    let sp = &model.specimen;
    let pos = |e: f64| e.max(0.0);
    let d = sp.height() - x.z1;
    let step = d * sp.tan_alpha_b();
    let mut v = pos(sp.h - x.z1) + pos(x.z1 - (sp.height() - sp.h));
    for (w, len) in [(x.wall_x(), sp.length_x()), (x.wall_y(), sp.length_y())] {
        v += pos(sp.t - w.base) + pos(w.base - w.green) + pos(-w.red);
        v += pos(w.green + w.red - len) + pos(w.green + w.red - w.base - step);
        // m = 1 needs a red block of finite rotation d / red.
        if model.mechanism == crate::Mechanism::Flexural {
            v += pos(1e-3 * sp.v() - w.red);
        }
    }
    v
}

impl CostFunction for Problem<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, p: &Self::Param) -> Result<f64, Error> {
        let x = geometry(p);
        let viol = violation(self.model, &x);
        if viol > 0.0 || p.iter().any(|c| !c.is_finite()) {
            return Ok(1e3 + 1e3 * viol);
        }
        Ok(self.model.evaluate_unchecked(&x, self.alpha).lambda_alpha)
    }
}

/// Nelder-Mead from `start` (a grid optimum); returns the better of the result and the start.
pub(crate) fn nelder_mead(model: &CornerModel, start: &Geometry, alpha: f64) -> Evaluation {
    let sp = &model.specimen;
    let p0 = vec![
        start.x1, start.x2, start.x3, start.y1, start.y2, start.y3, start.z1,
    ];
    let mut best = model.evaluate_unchecked(start, alpha);
    // Two restarts from the last best point with a fresh simplex: Nelder-Mead stalls on the
    // penalty's edges, a new simplex lets it slide along an active constraint.
    let mut p = p0;
    for step in [0.25, 0.1, 0.03] {
        let mut simplex = vec![p.clone()];
        for i in 0..7 {
            let mut q = p.clone();
            let scale = if i == 6 { sp.h } else { sp.v() };
            // Step inwards where an upper bound is likely active.
            q[i] -= step * scale;
            simplex.push(q);
        }
        let Ok(solver) = NelderMead::new(simplex).with_sd_tolerance(1e-12) else {
            break;
        };
        let problem = Problem { model, alpha };
        let Ok(res) = Executor::new(problem, solver)
            .configure(|s| s.max_iters(3000))
            .run()
        else {
            break;
        };
        let state = res.state();
        let Some(q) = state.best_param.clone() else {
            break;
        };
        let x = geometry(&q);
        if violation(model, &x) == 0.0 {
            let e = model.evaluate_unchecked(&x, alpha);
            if e.lambda_alpha < best.lambda_alpha {
                best = e;
                p = q;
            }
        }
    }
    best
}
