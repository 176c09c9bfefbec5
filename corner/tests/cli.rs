//! The `rocking-corner` binary: its JSON records, its body file and its refusals, against the
//! library called directly.

use std::process::Command;

use corner::{corner_multiplier, rocking_body, CornerModel, Direction};
use serde_json::Value;

fn run(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_rocking-corner"))
        .args(args)
        .output()
        .expect("the binary runs")
}

#[test]
fn json_records_carry_every_documented_key() {
    let out = run(&[
        "--alpha", "0.785398", "0.981748", "--k", "0.3", "--m", "1", "--json",
    ]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let records: Vec<Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(records.len(), 2);
    let model = CornerModel::paper(1, 0.3).unwrap();
    for r in &records {
        for key in [
            "alpha",
            "lambda_alpha",
            "lambda_X",
            "lambda_Y",
            "geometry",
            "work_X",
            "work_Y",
        ] {
            assert!(r.get(key).is_some(), "{key} missing in {r}");
        }
        for key in ["X1", "X2", "X3", "Y1", "Y2", "Y3", "Z1"] {
            assert!(r["geometry"][key].is_f64(), "{key}");
        }
        for key in [
            "stabilising",
            "overturning",
            "friction_ip",
            "friction_oop",
            "torsion",
            "torsion_lambda",
            "dissipation",
        ] {
            assert!(
                r["work_X"][key].is_f64() && r["work_Y"][key].is_f64(),
                "{key}"
            );
        }
        let alpha = r["alpha"].as_f64().unwrap();
        let lib = corner_multiplier(&model, alpha).unwrap();
        assert_eq!(r["lambda_alpha"].as_f64().unwrap(), lib.grid.lambda_alpha);
    }
}

#[test]
fn body_file_holds_fmu_parameters_only() {
    let dir = std::env::temp_dir().join(format!("rocking-corner-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("body.json");
    let out = run(&[
        "--alpha",
        "1.5707963267948966",
        "--no-refine",
        "--body",
        path.to_str().unwrap(),
        "--body-kind",
        "geometric",
    ]);
    assert!(out.status.success());
    let body: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    let names: Vec<&str> = body
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    // Every key is a RockingBlock FMU variable (docs/model.md section 5).
    let fmu = [
        "massModel",
        "W",
        "hG",
        "Ic",
        "shape",
        "B",
        "L",
        "interface",
        "restitution",
        "g",
    ];
    for n in &names {
        assert!(fmu.contains(n), "{n} is not an FMU parameter");
    }
    let model = CornerModel::paper(1, 0.3).unwrap();
    let r = corner_multiplier(&model, std::f64::consts::FRAC_PI_2).unwrap();
    let b = rocking_body(&model, &r.grid.geometry, Direction::Y).unwrap();
    assert_eq!(body["W"].as_f64().unwrap(), b.weight);
    assert_eq!(body["B"].as_f64().unwrap(), 2.0 * b.b);
    assert_eq!(body["massModel"], "lumped");
}

#[test]
fn bad_input_is_refused_by_name() {
    for (args, name) in [
        (vec!["--k", "1.5"], "invalid k"),
        (vec!["--mu", "0"], "invalid mu"),
        (vec!["--courses", "1"], "invalid courses"),
        (vec!["--t", "-0.1"], "invalid t"),
        (vec!["--alpha", "2"], "invalid alpha"),
        (vec!["--m", "3"], "invalid m"),
        (vec!["--geometry", "0.1,0.1"], "invalid geometry"),
    ] {
        let out = run(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert!(err.contains(name), "{args:?}: {err}");
    }
}

#[test]
fn pi_over_2_written_to_ten_digits_is_pi_over_2() {
    // 1.570796327 lies 2e-10 above pi/2: the same orientation as typed by a person
    let out = run(&[
        "--alpha",
        "1.570796327",
        "--k",
        "0.3",
        "--m",
        "1",
        "--json",
        "--no-refine",
    ]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let r: Value = serde_json::from_str(String::from_utf8(out.stdout).unwrap().trim()).unwrap();
    let model = CornerModel::paper(1, 0.3).unwrap();
    let exact = corner_multiplier(&model, std::f64::consts::FRAC_PI_2).unwrap();
    let lambda = r["lambda_alpha"].as_f64().unwrap();
    assert!((lambda - exact.grid.lambda_alpha).abs() <= 1e-9 * exact.grid.lambda_alpha);
    assert_eq!(run(&["--alpha", "1.5708"]).status.code(), Some(2)); // 3.7e-6 above: refused
}
