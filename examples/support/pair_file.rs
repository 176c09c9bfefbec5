//! The record-pair files the spatial examples read
//! (`#[path = "support/pair_file.rs"] mod pair_file;`), written by
//! `examples/dharahara_space.py` and `benches/spatial_record.py`: a first
//! line `# name bearing_x` (underscores for spaces; `none` without a
//! bearing), the time step (s), then `agx agy av` per sample (m/s²).

#![allow(dead_code)] // each example uses part of it

/// One record pair on one time base.
pub struct PairFile {
    pub name: String,
    /// Compass bearing of x, degrees, when the labels give it.
    pub bearing_x: Option<f64>,
    /// Time step, s.
    pub dt: f64,
    /// `[agx, agy, av]` per sample, m/s².
    pub samples: Vec<[f64; 3]>,
}

/// The file at `path`; panics naming the file and the line on a bad one
/// (a measurement's input, written by our own scripts).
pub fn read(path: &str) -> PairFile {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut lines = text.lines();
    let head = lines.next().unwrap_or_else(|| panic!("{path}: empty"));
    let mut words = head.trim_start_matches('#').split_whitespace();
    let name = words.next().unwrap_or("?").replace('_', " ");
    let bearing_x = words.next().and_then(|b| b.parse::<f64>().ok());
    let number = |s: &str| -> f64 { s.parse().unwrap_or_else(|e| panic!("{path}: {s:?}: {e}")) };
    let dt = number(
        lines
            .next()
            .unwrap_or_else(|| panic!("{path}: no time step"))
            .trim(),
    );
    let samples = lines
        .map(|line| {
            let v: Vec<f64> = line.split_whitespace().map(number).collect();
            assert_eq!(v.len(), 3, "{path}: {line:?}: three numbers expected");
            [v[0], v[1], v[2]]
        })
        .collect();
    PairFile {
        name,
        bearing_x,
        dt,
        samples,
    }
}
