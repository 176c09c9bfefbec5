//! The exhaustive branch-and-bound search over joint-aligned geometries, then the
//! Nelder-Mead refinement: [`corner_multiplier`].

use serde::{Deserialize, Serialize};

use crate::error::CornerError;
use crate::refine;
use crate::virtual_work::{check_alpha, InPlane, OutOfPlane};
use crate::{CornerModel, Direction, Evaluation, Geometry, Mechanism, WallPart};

/// Result of [`corner_multiplier`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CornerResult {
    /// Load orientation from the x axis (rad).
    pub alpha: f64,
    /// Mechanism flag (0 rocking-sliding, 1 flexural).
    pub m: u32,
    pub k: f64,
    /// The joint-aligned optimum (exact on the grid): the reported multiplier.
    #[serde(flatten)]
    pub grid: Evaluation,
    /// Admissible joint-aligned geometries (the search is exhaustive over these).
    pub candidates: u64,
    /// Of those, the ones evaluated pair by pair; the rest were excluded by a lower bound.
    pub evaluated: u64,
    /// The continuous Nelder-Mead refinement from the grid optimum, when asked for.
    pub refined: Option<Evaluation>,
}

/// The admissible (green, red, base) triples of one wall, in half blocks, for n courses.
fn wall_triples(
    n: u32,
    base_min: u32,
    len_units: u32,
    red_min: u32,
    step_units: u32,
) -> Vec<(u32, u32, u32)> {
    let mut out = Vec::new();
    for base in base_min..=len_units {
        for green in base..=len_units {
            for red in red_min..=(len_units - green) {
                if green + red - base <= step_units.saturating_mul(n) {
                    out.push((green, red, base));
                }
            }
        }
    }
    out
}

/// Minimum of lambda_alpha over the joint-aligned geometries, refined by Nelder-Mead when
/// `options.refine`; `alpha` in rad from the x axis, in [0, pi/2].
pub fn corner_multiplier(model: &CornerModel, alpha: f64) -> Result<CornerResult, CornerError> {
    let alpha = check_alpha(alpha)?;
    let (grid, counts) = grid_search(model, alpha);
    let refined = if model.options.refine {
        Some(refine::nelder_mead(model, &grid.geometry, alpha))
    } else {
        None
    };
    Ok(CornerResult {
        alpha,
        m: model.mechanism.m(),
        k: model.k,
        grid,
        candidates: counts.candidates,
        evaluated: counts.evaluated,
        refined,
    })
}

/// Exhaustive search over joint-aligned geometries: the hinge on a bed joint `Z1 = j h`, every
/// length a multiple of v, cracks no flatter than the running-bond step. Each wall's triples
/// are reduced once per hinge level to four partial sums (in-plane and out-of-plane numerator
/// and denominator), so a candidate pair costs two divisions.
fn grid_search(model: &CornerModel, alpha: f64) -> (Evaluation, Counts) {
    let sp = &model.specimen;
    let v = sp.v();
    let (s, c) = alpha.sin_cos();
    let (c2, s2) = (c * c, s * s);
    // Smallest number of half blocks that reaches the thickness t (X3, Y3 >= t).
    let base_min = ((sp.t / v) - 1e-9).ceil().max(1.0) as u32;
    let red_min = match model.mechanism {
        Mechanism::Flexural => 1,
        Mechanism::RockingSliding => 0,
    };
    // The crack constraint extent <= d tan(alpha_b) = n v: one half block per course.
    let step_units = 1;
    let mut best: Option<(f64, Geometry)> = None;
    let mut candidates = 0u64;
    let mut evaluated = 0u64;
    for j in 1..sp.courses {
        let z1 = f64::from(j) * sp.h;
        let d = sp.height() - z1;
        let n = sp.courses - j;
        let tx = wall_triples(n, base_min, 2 * sp.blocks_x, red_min, step_units);
        let ty = wall_triples(n, base_min, 2 * sp.blocks_y, red_min, step_units);
        let part = |t: &(u32, u32, u32)| WallPart {
            green: f64::from(t.0) * v,
            red: f64::from(t.1) * v,
            base: f64::from(t.2) * v,
        };
        let px: Vec<(InPlane, OutOfPlane)> = tx
            .iter()
            .map(|t| (model.in_plane(part(t), d), model.out_of_plane(part(t), d)))
            .collect();
        let py: Vec<(InPlane, OutOfPlane)> = ty
            .iter()
            .map(|t| (model.in_plane(part(t), d), model.out_of_plane(part(t), d)))
            .collect();
        // Partial sums: numerator and denominator shares of each wall in each role.
        let sums = |p: &[(InPlane, OutOfPlane)]| -> Vec<[f64; 6]> {
            p.iter()
                .map(|(ip, oop)| {
                    [
                        ip.stabilising + ip.friction,
                        ip.overturning,
                        oop.stabilising + oop.friction + oop.torsion,
                        oop.overturning + oop.torsion_lambda,
                        oop.weight_red,
                        oop.fmax,
                    ]
                })
                .collect()
        };
        let sx = sums(&px);
        let sy = sums(&py);
        candidates += (sx.len() * sy.len()) as u64;
        // Branch and bound. For a WX triple and a set of WY triples, the numerators are
        // smallest and the denominators largest at the set's extremes, so no pair can go below
        //   c2 (a0 + min b2)/(a1 + max b3) + s2 (min b0 + a2)/(max b1 + a3).
        // The formula without the torsion clamp is itself a lower bound (the clamp only raises
        // lambda), and correctly rounded + and / are monotone, so the bound holds in floating
        // point. Rows (WX triples) are visited by increasing bound over all of WY, the WY list in
        // chunks of neighbours (similar triples) with their own bounds; ties are broken by the
        // listing order, so the result is the one the plain double loop gives.
        let extremes = |ys: &[[f64; 6]]| {
            ys.iter()
                .fold([f64::INFINITY, 0.0, f64::INFINITY, 0.0], |e, b| {
                    [
                        e[0].min(b[0]),
                        e[1].max(b[1]),
                        e[2].min(b[2]),
                        e[3].max(b[3]),
                    ]
                })
        };
        let bound = |a: &[f64; 6], e: &[f64; 4]| {
            c2 * ((a[0] + e[2]) / (a[1] + e[3])) + s2 * ((e[0] + a[2]) / (e[1] + a[3]))
        };
        const CHUNK: usize = 16;
        let chunks: Vec<[f64; 4]> = sy.chunks(CHUNK).map(extremes).collect();
        let all = extremes(&sy);
        let mut rows: Vec<(f64, usize)> = sx
            .iter()
            .enumerate()
            .map(|(i, a)| (bound(a, &all), i))
            .collect();
        rows.sort_by(|p, q| p.0.total_cmp(&q.0).then(p.1.cmp(&q.1)));
        let global = best.map_or(f64::INFINITY, |b| b.0);
        // Can a candidate of lower bound `lb` still win? Within the level a tie may win on
        // order; against an earlier level it must be strictly lower.
        let open = |lb: f64, level: f64| lb <= level && lb < global;
        let mut level_best = (f64::INFINITY, usize::MAX, usize::MAX);
        for &(row_bound, ix) in &rows {
            if !open(row_bound, level_best.0) {
                break;
            }
            let a = &sx[ix];
            for (ci, e) in chunks.iter().enumerate() {
                if !open(bound(a, e), level_best.0) {
                    continue;
                }
                let start = ci * CHUNK;
                let end = (start + CHUNK).min(sy.len());
                evaluated += (end - start) as u64;
                for (iy, b) in sy.iter().enumerate().take(end).skip(start) {
                    let mut lx = (a[0] + b[2]) / (a[1] + b[3]);
                    let mut ly = (b[0] + a[2]) / (b[1] + a[3]);
                    // The torsion clamp [A7] is rare: redo that direction exactly when it binds.
                    if 0.5 * lx * b[4] > b[5] || 0.5 * ly * a[4] > a[5] {
                        let x = geometry_of(&tx[ix], &ty[iy], v, z1);
                        lx = model.direction_terms(&x, Direction::X).lambda;
                        ly = model.direction_terms(&x, Direction::Y).lambda;
                    }
                    let l = c2 * lx + s2 * ly;
                    if l < level_best.0
                        || (l == level_best.0 && (ix, iy) < (level_best.1, level_best.2))
                    {
                        level_best = (l, ix, iy);
                    }
                }
            }
        }
        if level_best.0 < best.map_or(f64::INFINITY, |b| b.0) {
            let x = geometry_of(&tx[level_best.1], &ty[level_best.2], v, z1);
            best = Some((level_best.0, x));
        }
    }
    let (_, x) = best.expect("a course has at least one admissible geometry");
    (
        model.evaluate_unchecked(&x, alpha),
        Counts {
            candidates,
            evaluated,
        },
    )
}

/// Candidate geometries of a grid search: all admissible ones, and those evaluated after the
/// row bound.
#[derive(Debug, Clone, Copy)]
struct Counts {
    candidates: u64,
    evaluated: u64,
}

fn geometry_of(tx: &(u32, u32, u32), ty: &(u32, u32, u32), v: f64, z1: f64) -> Geometry {
    Geometry {
        x1: f64::from(tx.0) * v,
        x2: f64::from(tx.1) * v,
        x3: f64::from(tx.2) * v,
        y2: f64::from(ty.0) * v,
        y1: f64::from(ty.1) * v,
        y3: f64::from(ty.2) * v,
        z1,
    }
}
