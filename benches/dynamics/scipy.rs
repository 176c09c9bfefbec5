//! SciPy's `solve_ivp` DOP853 as a second, independent implementation
//! (`benches/scipy_reference.py`), and the speed-up tables against it.

pub fn scipy(request: &str) -> Option<serde_json::Value> {
    if std::env::var("BENCH_NO_SCIPY").is_ok() {
        return None;
    }
    let py = concat!(env!("CARGO_MANIFEST_DIR"), "/.venv/bin/python");
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/scipy_reference.py");
    if !std::path::Path::new(py).exists() {
        eprintln!("(no {py}: run tools/venv.sh for the SciPy comparison)");
        return None;
    }
    let out = std::process::Command::new(py)
        .arg(script)
        .arg(request)
        .output()
        .ok()?;
    if !out.status.success() {
        eprintln!(
            "scipy_reference.py failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        return None;
    }
    match serde_json::from_slice(&out.stdout) {
        Ok(v) => Some(v),
        Err(e) => {
            eprintln!("scipy_reference.py printed no valid JSON: {e}");
            None
        }
    }
}

/// Reading SciPy's answer: a number (`null`, for a quantity SciPy did not
/// reach, reads as NaN) and an array (empty if absent).
pub trait Json {
    fn num(&self) -> f64;
    fn arr(&self) -> &[serde_json::Value];
}

impl Json for serde_json::Value {
    fn num(&self) -> f64 {
        self.as_f64().unwrap_or(f64::NAN)
    }
    fn arr(&self) -> &[serde_json::Value] {
        self.as_array().map_or(&[], |v| v.as_slice())
    }
}

pub fn json_list(xs: &[f64]) -> String {
    let v: Vec<String> = xs.iter().map(|x| format!("{x:e}")).collect();
    format!("[{}]", v.join(","))
}

/// Time of ours against SciPy: at the same rtol, and at equal error
/// (ours interpolated in log-log at SciPy's error).
pub fn speedups(case: &str, ours: &[(f64, f64, f64)], theirs: &[(f64, f64, f64)]) {
    println!("{case}: speed-up over SciPy DOP853");
    for &(rtol, err, secs) in theirs {
        let same = ours.iter().find(|o| o.0 == rtol).map(|o| secs / o.2);
        // ours at equal error: log-linear interpolation of time vs error
        let mut at_err = None;
        for w in ours.windows(2) {
            let (e0, e1) = (w[0].1, w[1].1);
            if (e0 - err) * (e1 - err) <= 0.0 && e0 > 0.0 && e1 > 0.0 && e0 != e1 {
                let f = (err.ln() - e0.ln()) / (e1.ln() - e0.ln());
                let t = (w[0].2.ln() + f * (w[1].2.ln() - w[0].2.ln())).exp();
                at_err = Some(secs / t);
            }
        }
        println!(
            "  rtol {rtol:.0e}: SciPy error {err:.2e} in {:.3} ms; same rtol: {}; equal error: {}",
            secs * 1e3,
            same.map_or("-".into(), |x| format!("{x:.0}x")),
            at_err.map_or("(outside our range)".into(), |x| format!("{x:.0}x"))
        );
    }
}
