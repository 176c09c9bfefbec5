//! `cargo xtask wheel`: the Python package `rocking` as platform wheels that
//! need neither the clone nor Rust, and its sdist, in `target/wheels`.
//!
//! Each wheel carries, in `rocking/_bundled/` (laid out like a clone, which
//! is how python/rocking/paths.py finds it): both FMUs in both standards
//! (`target/fmu`, `target/fmu/fmi3`), the native stepping loop and
//! `rocking-corner` built for its platform (`target/release`), a sample of the
//! shipped records with their provenance and terms (`data/ground-motions`),
//! the example study files (`examples`), the licences of every crate compiled
//! into its binaries (`THIRD-PARTY-LICENSES.txt`, also in the wheel's
//! `.dist-info/licenses`) and `BUILD.json` (the commit). The
//! helpers are built like the FMUs' binaries (`target/platforms/<platform>`):
//! linux64 by cargo-zigbuild against glibc 2.17 (manylinux2014), win64 by
//! mingw-w64. tools/wheel.py turns the staged folder and setuptools' pure
//! wheel into the platform wheel.

use std::env::consts::{DLL_PREFIX, DLL_SUFFIX, EXE_SUFFIX};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::{
    all_messages, c_runtime, licences, linux64_cargo, package, root, shipped_profile, target_dir,
    win64_cargo, Res, LINUX64_TARGET, MODELS, WIN64_TARGET,
};

/// A wheel's platform: how its helpers are built and named.
struct Platform {
    /// The folder of its build under target/platforms (as the FMUs').
    name: &'static str,
    target: &'static str,
    /// The wheel's platform tag.
    tag: &'static str,
    /// The stepping loop's file name (python/rocking/stepper.py looks for it).
    stepper: &'static str,
    /// The corner binary's file name.
    corner: &'static str,
    /// cargo set up for the platform, or why it cannot be.
    cargo: fn() -> Res<Result<Command, String>>,
    /// The helpers' `strip` setting. The Windows binaries lose their COFF
    /// symbol table (3470 symbols, 250 kB of rocking-corner.exe): Windows
    /// tools read PDB files, which the GNU toolchain does not write, so it
    /// only told a reader the build's function names. The Linux ones keep
    /// theirs for backtraces and profilers (the FMUs' libraries keep theirs
    /// on both platforms: `cargo xtask fmu`'s profile).
    strip: &'static str,
}

const PLATFORMS: [Platform; 2] = [
    Platform {
        name: "linux64",
        target: LINUX64_TARGET,
        tag: "manylinux2014_x86_64",
        stepper: "libfmu_stepper.so",
        corner: "rocking-corner",
        cargo: linux64_cargo,
        strip: "debuginfo",
    },
    Platform {
        name: "win64",
        target: WIN64_TARGET,
        tag: WIN64_TAG,
        stepper: "fmu_stepper.dll",
        corner: "rocking-corner.exe",
        cargo: win64_cargo,
        strip: "symbols",
    },
];

/// The sample of data/ground-motions a wheel carries: the records of the
/// README's examples and the tests' smallest, with the README that states
/// their provenance and terms.
const RECORDS: [&str; 3] = ["README.md", "katnp-standin", "usgs-lomaprieta-1989"];

/// The study files of the README's commands (examples/), with what they
/// name: fragility.toml's hazard curve; its records are `../data/ground-motions`,
/// the sample above.
const EXAMPLES: [&str; 4] = [
    "fragility.toml",
    "hazard-illustrative.csv",
    "sweep.toml",
    "cosim",
];

/// The workspace packages whose binaries a wheel carries: the FMUs' and the helpers'.
const SHIPPED: [&str; 5] = [
    "fmu-rocking",
    "fmu-shear-frame",
    "fmu-round-body",
    "fmu-stepper",
    "corner",
];

/// The licence file's name in the bundle (tools/wheel.py also puts it in .dist-info/licenses).
const LICENCES: &str = "THIRD-PARTY-LICENSES.txt";

/// The FMU archives of a model that `cargo xtask fmu` writes: 2.0, and 3.0 where it exports it.
fn archives(model: &crate::Model) -> Vec<String> {
    let name = format!("{}.fmu", model.identifier);
    let mut all = vec![name.clone()];
    if model.fmi3 {
        all.push(format!("fmi3/{name}"));
    }
    all
}

/// The win64 wheel's platform tag (its binaries carry mingw-w64's C runtime).
const WIN64_TAG: &str = "win_amd64";

/// `cargo xtask wheel [--reuse-fmus]`.
pub fn wheels(args: &[String]) -> Res<()> {
    let reuse = args.iter().any(|a| a == "--reuse-fmus");
    if let Some(other) = args.iter().find(|a| *a != "--reuse-fmus") {
        return Err(format!("wheel: unknown option {other:?}"));
    }
    let fmu_dir = target_dir().join("fmu");
    for model in MODELS {
        if !(reuse && archives(model).iter().all(|a| fmu_dir.join(a).is_file())) {
            package(model)?;
        }
    }
    let out = target_dir().join("wheels");
    fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    let commit = git_commit();
    for platform in &PLATFORMS {
        let cmd = (platform.cargo)()?.map_err(|why| format!("{}: {why}", platform.name))?;
        let (stepper, corner) = build_helpers(cmd, platform)?;
        let stage = target_dir().join("wheel").join(platform.name);
        let bundle = stage.join("_bundled");
        let helpers = [(platform.stepper, stepper), (platform.corner, corner)];
        stage_bundle(&bundle, &helpers, &commit, platform.tag)?;
        python(&[
            "tools/wheel.py",
            "--bundle",
            &bundle.display().to_string(),
            "--plat",
            platform.tag,
            "--out",
            &out.display().to_string(),
        ])?;
    }
    python(&[
        "tools/wheel.py",
        "--sdist",
        "--out",
        &out.display().to_string(),
    ])
}

/// Fills a fresh `bundle` folder: the FMUs of target/fmu (2.0 and 3.0), the
/// helpers (file name in the bundle, built file), the sample records, the
/// example studies, the licence file, BUILD.json.
fn stage_bundle(bundle: &Path, helpers: &[(&str, PathBuf)], commit: &str, tag: &str) -> Res<()> {
    if bundle.exists() {
        fs::remove_dir_all(bundle).map_err(|e| format!("{}: {e}", bundle.display()))?;
    }
    for model in MODELS {
        for name in archives(model) {
            let fmu = target_dir().join("fmu").join(&name);
            copy(&fmu, &bundle.join("target/fmu").join(&name))?;
        }
    }
    for (name, built) in helpers {
        copy(built, &bundle.join("target/release").join(name))?;
    }
    for entry in RECORDS {
        copy_tree(
            &root().join("data/ground-motions").join(entry),
            &bundle.join("data/ground-motions").join(entry),
        )?;
    }
    for entry in EXAMPLES {
        copy_tree(
            &root().join("examples").join(entry),
            &bundle.join("examples").join(entry),
        )?;
    }
    let what = format!("the rocking wheel for {tag} (its FMUs, stepping loop and rocking-corner)");
    let mut text = licences::file(&SHIPPED, &what)?;
    if tag == WIN64_TAG {
        text.push_str(&c_runtime::section()?);
    }
    write(&bundle.join(LICENCES), text.as_bytes())?;
    let info = serde_json::json!({ "commit": commit, "platform": tag });
    write(&bundle.join("BUILD.json"), info.to_string().as_bytes())
}

/// `cargo xtask bundle DIR`: the FMUs and the helpers built for this machine
/// (target/release), staged into DIR: what setup.py puts into a wheel built
/// from the sdist.
pub fn bundle(args: &[String]) -> Res<()> {
    let [dir] = args else {
        return Err("usage: cargo xtask bundle DIR".into());
    };
    for model in MODELS {
        package(model)?;
    }
    let mut cmd = crate::cargo();
    helpers_build(&mut cmd);
    let release = target_dir().join("release");
    let status = cmd.status().map_err(|e| format!("cargo build: {e}"))?;
    if !status.success() {
        return Err(format!(
            "cargo build of fmu-stepper and corner failed ({status})"
        ));
    }
    let stepper = format!("{DLL_PREFIX}fmu_stepper{DLL_SUFFIX}");
    let corner = format!("rocking-corner{EXE_SUFFIX}");
    let helpers = [
        (stepper.as_str(), release.join(&stepper)),
        (corner.as_str(), release.join(&corner)),
    ];
    stage_bundle(Path::new(dir), &helpers, &git_commit(), "native")
}

/// `cargo build` of the helpers a wheel carries: the stepping loop's library
/// and rocking-corner.
fn helpers_build(cmd: &mut Command) {
    cmd.current_dir(root()).args([
        "build",
        "--release",
        "--package",
        "fmu-stepper",
        "--lib",
        "--package",
        "corner",
        "--bin",
        "rocking-corner",
    ]);
}

/// Builds fmu-stepper's library and rocking-corner for the platform in its
/// own target dir; returns their paths.
fn build_helpers(mut cmd: Command, platform: &Platform) -> Res<(PathBuf, PathBuf)> {
    helpers_build(&mut cmd);
    cmd.args(["--target", platform.target, "--target-dir"]);
    cmd.arg(target_dir().join("platforms").join(platform.name));
    shipped_profile(&mut cmd);
    cmd.env("CARGO_PROFILE_RELEASE_STRIP", platform.strip);
    let messages = all_messages(cmd)?;
    let artifact = |target: &str, file: &str| {
        messages
            .iter()
            .filter(|v| v["reason"] == "compiler-artifact" && v["target"]["name"] == target)
            .flat_map(|v| v["filenames"].as_array().into_iter().flatten())
            .filter_map(|f| f.as_str())
            .find(|f| f.ends_with(file))
            .map(PathBuf::from)
            .ok_or_else(|| format!("cargo reported no {file} for {}", platform.target))
    };
    let stepper = artifact("fmu_stepper", platform.stepper)?;
    let corner = artifact("rocking-corner", platform.corner)?;
    Ok((stepper, corner))
}

/// HEAD of the clone, "-dirty" when tracked files differ from it; "unknown"
/// without git (an sdist's build).
fn git_commit() -> String {
    let git = |args: &[&str]| Command::new("git").current_dir(root()).args(args).output();
    match git(&["rev-parse", "HEAD"]) {
        Ok(head) if head.status.success() => {
            let dirty = git(&["status", "--porcelain", "--untracked-files=no"])
                .is_ok_and(|s| !s.stdout.is_empty());
            let sha = String::from_utf8_lossy(&head.stdout).trim().to_string();
            if dirty {
                format!("{sha}-dirty")
            } else {
                sha
            }
        }
        _ => "unknown".into(),
    }
}

/// Runs .venv's Python (else python3) in the workspace root.
fn python(args: &[&str]) -> Res<()> {
    let venv = root().join(".venv/bin/python");
    let exe = if venv.is_file() {
        venv
    } else {
        PathBuf::from("python3")
    };
    let status = Command::new(&exe)
        .current_dir(root())
        .args(args)
        .status()
        .map_err(|e| format!("cannot run {}: {e}", exe.display()))?;
    if !status.success() {
        return Err(format!(
            "{} {} failed ({status})",
            exe.display(),
            args.join(" ")
        ));
    }
    Ok(())
}

fn write(path: &Path, data: &[u8]) -> Res<()> {
    if let Some(dir) = path.parent() {
        fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    fs::write(path, data).map_err(|e| format!("{}: {e}", path.display()))
}

fn copy(from: &Path, to: &Path) -> Res<()> {
    if let Some(dir) = to.parent() {
        fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    fs::copy(from, to)
        .map(|_| ())
        .map_err(|e| format!("{} -> {}: {e}", from.display(), to.display()))
}

/// Copies a file, or a folder's files (one level: the record folders are flat).
fn copy_tree(from: &Path, to: &Path) -> Res<()> {
    if from.is_file() {
        return copy(from, to);
    }
    let entries = fs::read_dir(from).map_err(|e| format!("{}: {e}", from.display()))?;
    for entry in entries {
        let path = entry
            .map_err(|e| format!("{}: {e}", from.display()))?
            .path();
        if path.is_file() {
            copy(
                &path,
                &to.join(path.file_name().expect("a file has a name")),
            )?;
        }
    }
    Ok(())
}
