//! `cargo xtask fmu`: builds the release cdylib and writes
//! `target/fmu/RockingBlock.fmu` (modelDescription.xml,
//! binaries/linux64/RockingBlock.so, documentation/index.html), reproducibly:
//! fixed timestamps and permissions, sorted entries. The XML and the page are
//! the very files `fmu-rocking/build.rs` generated for the binary, whose
//! embedded GUID is checked against the XML's.
//!
//! The same build also makes the `run_direct` example (the Rust engine run
//! directly, for the fmpy tests' comparisons).

use std::env;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, DateTime, ZipWriter};

const MODEL_IDENTIFIER: &str = "RockingBlock";

type Res<T> = Result<T, String>;

fn main() {
    let args: Vec<String> = env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("fmu") => fmu().map(|_| ()),
        Some("crosscheck") => crosscheck(),
        Some("-h") | Some("--help") | None => {
            usage();
            Ok(())
        }
        Some(other) => {
            usage();
            Err(format!("unknown task {other:?}"))
        }
    };
    if let Err(e) = result {
        eprintln!("xtask: error: {e}");
        std::process::exit(1);
    }
}

fn usage() {
    eprintln!(
        "usage: cargo xtask <task>\n\n\
         tasks:\n  \
         fmu          build the release library and write target/fmu/{MODEL_IDENTIFIER}.fmu\n               \
         (and target/release/examples/run_direct)\n  \
         crosscheck   the FMU, then FMI cross-check artefacts (FMU, input, reference\n               \
         results from the engine run directly, options, README) under\n               \
         target/cross-check/fmus/2.0/cs/linux64/..."
    );
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the workspace")
        .to_path_buf()
}

fn target_dir() -> PathBuf {
    match env::var_os("CARGO_TARGET_DIR") {
        Some(p) => {
            let p = PathBuf::from(p);
            if p.is_absolute() {
                p
            } else {
                root().join(p)
            }
        }
        None => root().join("target"),
    }
}

/// What the release build produced.
struct Built {
    library: PathBuf,
    out_dir: PathBuf,
    run_direct: Option<PathBuf>,
}

/// The package directory of a cargo `package_id` (`path+file:///dir#...`).
fn package_dir(id: &str) -> Option<PathBuf> {
    let rest = id.strip_prefix("path+file://")?;
    let path = rest.split('#').next()?;
    Some(PathBuf::from(path))
}

fn build() -> Res<Built> {
    let cargo = env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let output = Command::new(cargo)
        .current_dir(root())
        .args([
            "build",
            "--release",
            "--package",
            "fmu-rocking",
            "--lib",
            "--example",
            "run_direct",
            "--message-format=json-render-diagnostics",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    if !output.status.success() {
        return Err(format!("cargo build failed ({})", output.status));
    }
    let fmu_dir = root().join("fmu-rocking");
    let (mut library, mut out_dir, mut run_direct) = (None, None, None);
    for line in String::from_utf8_lossy(&output.stdout).lines() {
        let Ok(v) = serde_json::from_str::<serde_json::Value>(line) else {
            continue;
        };
        let id = v["package_id"].as_str().unwrap_or("");
        let ours = package_dir(id).is_some_and(|d| d == fmu_dir);
        match v["reason"].as_str() {
            Some("build-script-executed") if ours => {
                out_dir = v["out_dir"].as_str().map(PathBuf::from);
            }
            Some("compiler-artifact") if ours => {
                let name = v["target"]["name"].as_str().unwrap_or("");
                let kinds: Vec<&str> = v["target"]["kind"]
                    .as_array()
                    .map(|a| a.iter().filter_map(|k| k.as_str()).collect())
                    .unwrap_or_default();
                if name == "fmu_rocking" && kinds.contains(&"cdylib") {
                    library = v["filenames"].as_array().and_then(|f| {
                        f.iter()
                            .filter_map(|x| x.as_str())
                            .find(|x| x.ends_with(".so"))
                            .map(PathBuf::from)
                    });
                }
                if name == "run_direct" {
                    run_direct = v["executable"].as_str().map(PathBuf::from);
                }
            }
            _ => {}
        }
    }
    Ok(Built {
        library: library.ok_or("cargo reported no fmu_rocking cdylib")?,
        out_dir: out_dir.ok_or("cargo reported no build-script output for fmu-rocking")?,
        run_direct,
    })
}

fn read(p: &Path) -> Res<Vec<u8>> {
    fs::read(p).map_err(|e| format!("{}: {e}", p.display()))
}

fn contains(haystack: &[u8], needle: &[u8]) -> bool {
    haystack.windows(needle.len()).any(|w| w == needle)
}

/// Writes the archive: sorted entries, fixed time stamps and permissions.
fn write_fmu(path: &Path, entries: &mut [(String, Vec<u8>, u32)]) -> Res<()> {
    entries.sort_by(|a, b| a.0.cmp(&b.0));
    let tmp = path.with_extension("fmu.tmp");
    let file = fs::File::create(&tmp).map_err(|e| format!("{}: {e}", tmp.display()))?;
    let mut zip = ZipWriter::new(file);
    for (name, data, mode) in entries.iter() {
        let opts = SimpleFileOptions::default()
            .compression_method(CompressionMethod::Deflated)
            .compression_level(Some(9))
            .last_modified_time(DateTime::default())
            .unix_permissions(*mode);
        zip.start_file(name.as_str(), opts)
            .map_err(|e| format!("zip {name}: {e}"))?;
        zip.write_all(data)
            .map_err(|e| format!("zip {name}: {e}"))?;
    }
    zip.finish().map_err(|e| format!("zip: {e}"))?;
    fs::rename(&tmp, path).map_err(|e| format!("{}: {e}", path.display()))
}

fn fmu() -> Res<PathBuf> {
    Ok(package()?.0)
}

/// Builds and packages; returns the archive and the build's products.
fn package() -> Res<(PathBuf, Built)> {
    let built = build()?;
    let xml = read(&built.out_dir.join("modelDescription.xml"))?;
    let guid = String::from_utf8(read(&built.out_dir.join("guid.txt"))?)
        .map_err(|e| format!("guid.txt: {e}"))?;
    let html = read(&built.out_dir.join("index.html"))?;
    let library = read(&built.library)?;
    if !contains(&xml, format!("guid=\"{guid}\"").as_bytes()) {
        return Err(format!(
            "modelDescription.xml does not carry the GUID {guid}"
        ));
    }
    if !contains(&library, guid.as_bytes()) {
        return Err(format!(
            "{} does not embed the GUID {guid} of the generated modelDescription.xml",
            built.library.display()
        ));
    }
    let dir = target_dir().join("fmu");
    fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let path = dir.join(format!("{MODEL_IDENTIFIER}.fmu"));
    let mut entries = vec![
        ("modelDescription.xml".to_string(), xml, 0o644),
        (
            format!("binaries/linux64/{MODEL_IDENTIFIER}.so"),
            library,
            0o755,
        ),
        ("documentation/index.html".to_string(), html, 0o644),
    ];
    write_fmu(&path, &mut entries)?;
    let size = fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
    println!("{} ({size} bytes, GUID {guid})", path.display());
    if let Some(r) = &built.run_direct {
        println!("{}", r.display());
    }
    Ok((path, built))
}

/// The cross-check case: the default block on its crushing joint under a
/// decaying 1.5 Hz ground motion, sampled on the communication grid.
const CC_STEP: f64 = 0.01;
const CC_STOP: f64 = 10.0;
const CC_RELTOL: f64 = 1e-9;

fn cc_ground_motion(t: f64) -> f64 {
    3.0 * (2.0 * std::f64::consts::PI * 1.5 * t).sin() * (-0.3 * t).exp()
}

/// `cargo xtask crosscheck`: FMI cross-check artefacts for the FMU.
fn crosscheck() -> Res<()> {
    let (fmu_path, built) = package()?;
    let run_direct = built
        .run_direct
        .ok_or("cargo reported no run_direct executable")?;
    let version = env!("CARGO_PKG_VERSION");
    let dir = target_dir()
        .join("cross-check/fmus/2.0/cs/linux64")
        .join(MODEL_IDENTIFIER)
        .join(version)
        .join(MODEL_IDENTIFIER);
    fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let name = |suffix: &str| dir.join(format!("{MODEL_IDENTIFIER}{suffix}"));
    fs::copy(&fmu_path, name(".fmu")).map_err(|e| format!("copy the FMU: {e}"))?;

    // the input on the communication grid (t_k = k h, as a master computes it),
    // and the steps the engine takes with it: zero-order hold, as a master
    // without input derivatives applies it
    let n = (CC_STOP / CC_STEP).round() as usize;
    let grid: Vec<f64> = (0..=n).map(|k| k as f64 * CC_STEP).collect();
    let mut input = String::from("\"time\",\"ag\"\n");
    let mut steps = String::from("t_end,ag,dag\n");
    for (k, &t) in grid.iter().enumerate() {
        let a = cc_ground_motion(t);
        input.push_str(&format!("{t},{a}\n"));
        if k + 1 < grid.len() {
            steps.push_str(&format!("{},{a},0\n", grid[k + 1]));
        }
    }
    fs::write(name("_in.csv"), input).map_err(|e| format!("_in.csv: {e}"))?;
    let steps_file = dir.join("steps.tmp.csv");
    fs::write(&steps_file, steps).map_err(|e| format!("steps: {e}"))?;
    let out = Command::new(&run_direct)
        .arg("--steps")
        .arg(&steps_file)
        .args(["--tolerance", &format!("{CC_RELTOL:e}")])
        .output()
        .map_err(|e| format!("{}: {e}", run_direct.display()))?;
    let _ = fs::remove_file(&steps_file);
    if !out.status.success() {
        return Err(format!(
            "run_direct failed: {}",
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    // the cross-check rules want quoted names in the header
    let text = String::from_utf8_lossy(&out.stdout);
    let mut lines = text.lines();
    let header = lines.next().ok_or("run_direct printed nothing")?;
    let mut reference: String = header
        .split(',')
        .map(|h| format!("\"{h}\""))
        .collect::<Vec<_>>()
        .join(",");
    reference.push('\n');
    for l in lines {
        reference.push_str(l);
        reference.push('\n');
    }
    fs::write(name("_ref.csv"), reference).map_err(|e| format!("_ref.csv: {e}"))?;
    fs::write(
        name("_ref.opt"),
        format!("StepSize,{CC_STEP}\nStartTime,0.0\nStopTime,{CC_STOP}\nRelTol,{CC_RELTOL:e}\n"),
    )
    .map_err(|e| format!("_ref.opt: {e}"))?;
    fs::write(
        dir.join("README.md"),
        format!(
            "# {MODEL_IDENTIFIER} {version}\n\n\
             A rigid masonry block (0.5 m x 1 m x 2.5 m, 1800 kg/m3) rocking on a \
             mortar joint (kn = 5 GPa/m, crushing at fm = 5 MPa) under the horizontal \
             ground acceleration `ag` of `{MODEL_IDENTIFIER}_in.csv` \
             (3 m/s2 sin(2 pi 1.5 t) exp(-0.3 t)); all parameters at their start values.\n\n\
             The reference results come from the Rust engine run directly with the \
             input held constant over each communication step (its value at the step \
             start, no input derivatives), the relative tolerance of `_ref.opt`.\n\n\
             Generated by `cargo xtask crosscheck`.\n"
        ),
    )
    .map_err(|e| format!("README.md: {e}"))?;
    println!("{}", dir.display());
    Ok(())
}
