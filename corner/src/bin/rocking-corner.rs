//! `rocking-corner`: limit analysis of a dry-joint masonry corner for a list of load
//! orientations; a table, or one JSON object per orientation (`--json`); `--body FILE` writes
//! the rocking body of one orientation as RockingBlock FMU parameters.
// The options' doc comments are their `--help` text (clap), where [A3] names an
// assumption of docs/corner.md, not a link.
#![allow(rustdoc::broken_intra_doc_links)]

use std::io::Write;
use std::process::ExitCode;

/// Print to stdout, ignoring a closed pipe (`rocking-corner | head` must not panic).
macro_rules! out {
    ($($arg:tt)*) => {{
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}

use clap::{Parser, ValueEnum};
use corner::{
    body_direction, corner_multiplier, rocking_body, BodyKind, CornerModel, CornerResult, Geometry,
    Options, Specimen,
};
use serde::de::DeserializeOwned;
use serde_json::{json, Map, Value};

#[derive(Clone, Copy, Debug, ValueEnum)]
enum PresetArg {
    Paper,
    Literal,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum BodyArg {
    Geometric,
    Threshold,
}

/// Limit analysis of a dry-joint masonry corner (docs/corner.md). Lengths in m, angles in rad.
#[derive(Parser, Debug)]
#[command(name = "rocking-corner", version)]
struct Cli {
    /// Load orientations from the x axis (rad, 0..pi/2); default: the paper's five, pi/4..pi/2.
    #[arg(long, num_args = 1.., allow_negative_numbers = true)]
    alpha: Vec<f64>,
    /// Mechanism: 0 rocking-sliding, 1 horizontal flexure.
    #[arg(long, default_value_t = 1)]
    m: u32,
    /// Torsion reduction factor at uplifted hinges, in [0, 1].
    #[arg(long, default_value_t = 0.3, allow_negative_numbers = true)]
    k: f64,
    /// Block thickness = wall thickness (m).
    #[arg(long, allow_negative_numbers = true)]
    t: Option<f64>,
    /// Block length (m).
    #[arg(long, allow_negative_numbers = true)]
    l: Option<f64>,
    /// Block height (m).
    #[arg(long, allow_negative_numbers = true)]
    h: Option<f64>,
    /// Density (kg/m3).
    #[arg(long, allow_negative_numbers = true)]
    rho: Option<f64>,
    /// Joint friction coefficient.
    #[arg(long, allow_negative_numbers = true)]
    mu: Option<f64>,
    /// Number of courses.
    #[arg(long)]
    courses: Option<u32>,
    /// Full blocks per course of wall WX.
    #[arg(long)]
    blocks_x: Option<u32>,
    /// Full blocks per course of wall WY.
    #[arg(long)]
    blocks_y: Option<u32>,
    /// Option set: paper (default) or literal.
    #[arg(long, value_enum, default_value = "paper")]
    preset: PresetArg,
    /// Override [A3]: in-plane wedge bounded by the green or the outer line.
    #[arg(long, value_enum)]
    wedge: Option<WedgeArg>,
    /// Override [A4]: corner column in both walls or once.
    #[arg(long, value_enum)]
    corner_column: Option<ColumnArg>,
    /// Override [A5]: friction lever (n-1)h/3 (joints) or d/3 (third).
    #[arg(long, value_enum)]
    friction_lever: Option<LeverArg>,
    /// Override [A6]: friction weight by angles or tangents.
    #[arg(long, value_enum)]
    crack_ratio: Option<RatioArg>,
    /// Joints counted in Fmax: eq9 (n(n+1)/2) or inner (n(n-1)/2).
    #[arg(long, value_enum)]
    friction_joints: Option<JointsArg>,
    /// Evaluate this macroblock instead of searching: X1,X2,X3,Y1,Y2,Y3,Z1 (m).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    geometry: Option<Vec<f64>>,
    /// Skip the Nelder-Mead refinement (grid only).
    #[arg(long)]
    no_refine: bool,
    /// One JSON object per orientation instead of a table.
    #[arg(long)]
    json: bool,
    /// Write the rocking body of one orientation (see --body-alpha) as FMU parameters (JSON).
    #[arg(long, value_name = "FILE")]
    body: Option<std::path::PathBuf>,
    /// Orientation whose body --body writes (default: the last --alpha).
    #[arg(long, allow_negative_numbers = true)]
    body_alpha: Option<f64>,
    /// Which body --body writes: geometric (B = 2b) or threshold (B = 2 b_eq).
    #[arg(long, value_enum, default_value = "threshold")]
    body_kind: BodyArg,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum WedgeArg {
    Green,
    Outer,
}
#[derive(Clone, Copy, Debug, ValueEnum)]
enum ColumnArg {
    Both,
    Once,
}
#[derive(Clone, Copy, Debug, ValueEnum)]
enum LeverArg {
    Joints,
    Third,
}
#[derive(Clone, Copy, Debug, ValueEnum)]
enum RatioArg {
    Angle,
    Tan,
}
#[derive(Clone, Copy, Debug, ValueEnum)]
enum JointsArg {
    Eq9,
    Inner,
}

/// The library's value of a command-line choice. The CLI's enums (clap needs its own) use the
/// names the library's enums have in serde (lowercase), so one conversion serves them all.
fn same_name<A: ValueEnum, T: DeserializeOwned>(arg: A) -> T {
    let name = arg.to_possible_value().expect("no value is skipped");
    serde_json::from_value(Value::String(name.get_name().to_owned()))
        .expect("each CLI value names a library value")
}

fn model_of(cli: &Cli) -> Result<CornerModel, corner::CornerError> {
    let paper = Specimen::paper();
    let sp = Specimen {
        t: cli.t.unwrap_or(paper.t),
        l: cli.l.unwrap_or(paper.l),
        h: cli.h.unwrap_or(paper.h),
        rho: cli.rho.unwrap_or(paper.rho),
        mu: cli.mu.unwrap_or(paper.mu),
        courses: cli.courses.unwrap_or(paper.courses),
        blocks_x: cli.blocks_x.unwrap_or(paper.blocks_x),
        blocks_y: cli.blocks_y.unwrap_or(paper.blocks_y),
        ..paper
    };
    let mut o: Options = Options::preset(same_name(cli.preset));
    o.in_plane_wedge = cli.wedge.map_or(o.in_plane_wedge, same_name);
    o.corner_column = cli.corner_column.map_or(o.corner_column, same_name);
    o.friction_lever = cli.friction_lever.map_or(o.friction_lever, same_name);
    o.crack_ratio = cli.crack_ratio.map_or(o.crack_ratio, same_name);
    o.friction_joints = cli.friction_joints.map_or(o.friction_joints, same_name);
    o.refine = !cli.no_refine;
    CornerModel::new(sp, cli.m, cli.k, o)
}

fn json_of(r: &CornerResult) -> Value {
    let mut v = serde_json::to_value(r).expect("plain numbers serialise");
    if let Value::Object(ref mut map) = v {
        // `m` of the geometry's unit is stated once, as the brief of the output asks.
        map.insert("length_unit".into(), json!("m"));
    }
    v
}

fn table(rs: &[CornerResult]) {
    out!(
        "{:>8} {:>8} {:>9} {:>9} {:>9} {:>9} | {:>6} {:>6} {:>6} {:>6} {:>6} {:>6} {:>6}",
        "alpha",
        "deg",
        "lambda",
        "lam_X",
        "lam_Y",
        "lam_NM",
        "X1",
        "X2",
        "X3",
        "Y1",
        "Y2",
        "Y3",
        "Z1"
    );
    for r in rs {
        let g = &r.grid.geometry;
        let nm = r.refined.map_or(f64::NAN, |e| e.lambda_alpha);
        out!(
            "{:>8.5} {:>8.2} {:>9.4} {:>9.4} {:>9.4} {:>9.4} | {:>6.1} {:>6.1} {:>6.1} {:>6.1} {:>6.1} {:>6.1} {:>6.1}",
            r.alpha,
            r.alpha.to_degrees(),
            r.grid.lambda_alpha,
            r.grid.lambda_x,
            r.grid.lambda_y,
            nm,
            g.x1 * 1e3,
            g.x2 * 1e3,
            g.x3 * 1e3,
            g.y1 * 1e3,
            g.y2 * 1e3,
            g.y3 * 1e3,
            g.z1 * 1e3
        );
    }
    out!("(lengths in mm; lambda on the joint-aligned grid, lam_NM after Nelder-Mead)");
    out!("work terms per unit rotation (N m/rad): S O D_fIP D_fOOP D_tors Lambda");
    for r in rs {
        for (name, w) in [("X", r.grid.work_x), ("Y", r.grid.work_y)] {
            out!(
                "{:>8.5} {}: {:>9.4} {:>9.4} {:>9.4} {:>9.4} {:>9.4} {:>9.4}",
                r.alpha,
                name,
                w.stabilising,
                w.overturning,
                w.friction_ip,
                w.friction_oop,
                w.torsion,
                w.torsion_lambda
            );
        }
    }
}

fn run(cli: &Cli) -> Result<(), String> {
    let model = model_of(cli).map_err(|e| e.to_string())?;
    let alphas = if cli.alpha.is_empty() {
        (0..5)
            .map(|i| std::f64::consts::PI * f64::from(4 + i) / 16.0)
            .collect()
    } else {
        cli.alpha.clone()
    };
    if let Some(g) = &cli.geometry {
        if g.len() != 7 {
            return Err(format!(
                "invalid geometry: 7 comma-separated values X1,X2,X3,Y1,Y2,Y3,Z1 needed, got {}",
                g.len()
            ));
        }
    }
    let given = cli.geometry.as_ref().map(|g| Geometry {
        x1: g[0],
        x2: g[1],
        x3: g[2],
        y1: g[3],
        y2: g[4],
        y3: g[5],
        z1: g[6],
    });
    let solve = |a: f64| -> Result<CornerResult, String> {
        match &given {
            None => corner_multiplier(&model, a).map_err(|e| e.to_string()),
            Some(x) => {
                let e = model.evaluate(x, a).map_err(|e| e.to_string())?;
                Ok(CornerResult {
                    alpha: a,
                    m: model.mechanism.m(),
                    k: model.k,
                    grid: e,
                    candidates: 1,
                    evaluated: 1,
                    refined: None,
                })
            }
        }
    };
    let mut results = Vec::new();
    for &a in &alphas {
        results.push(solve(a)?);
    }
    if cli.json {
        for r in &results {
            out!("{}", json_of(r));
        }
    } else {
        table(&results);
    }
    if let Some(path) = &cli.body {
        let alpha = cli
            .body_alpha
            .unwrap_or(*alphas.last().expect("at least one"));
        let r = solve(alpha)?;
        let dir = body_direction(alpha);
        let body = rocking_body(&model, &r.grid.geometry, dir).map_err(|e| e.to_string())?;
        let kind: BodyKind = same_name(cli.body_kind);
        let mut map = Map::new();
        for (name, value) in body.fmu_parameters(kind, model.specimen.g) {
            map.insert(name.into(), serde_json::to_value(value).expect("number"));
        }
        // The file holds FMU parameters only (name -> value, enumerations by item name), so a
        // host can pass every entry to the FMU; where the body comes from goes to stderr.
        let text = serde_json::to_string_pretty(&Value::Object(map)).expect("plain values");
        eprintln!(
            "rocking-corner: {} body of alpha = {alpha} (direction {dir:?}): lambda = {:.4}, \
             lambda_rock = {:.4}, b = {:.4} m, b_eq = {:.4} m, hG = {:.4} m, theta_u = {:.4} rad -> {}",
            match kind {
                BodyKind::Geometric => "geometric",
                BodyKind::Threshold => "threshold-matched",
            },
            body.lambda,
            body.lambda_rock,
            body.b,
            body.b_eq,
            body.h_g,
            body.theta_u,
            path.display()
        );
        std::fs::write(path, text + "\n").map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(&cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("rocking-corner: {e}");
            ExitCode::from(2)
        }
    }
}
