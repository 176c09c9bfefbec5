//! `cargo xtask fmu`: builds the release cdylibs and writes
//! `target/fmu/RockingBlock.fmu`, `target/fmu/ShearFrame.fmu` and
//! `target/fmu/RoundBody.fmu` (modelDescription.xml, the binaries,
//! documentation/index.html), reproducibly: fixed timestamps and
//! permissions, sorted entries. The XML and the page are the very files each
//! crate's `build.rs` (`fmu-rocking`, `fmu-shear-frame`, `fmu-round-body`)
//! generated for its binary, whose embedded GUID is checked against the XML's.
//!
//! The binaries, each built in a target directory of its own under
//! `target/platforms/`, so that no build's linker or C compiler settings
//! reach another's artefacts:
//! - `binaries/linux64/<model>.so`: `cargo zigbuild` for
//!   `x86_64-unknown-linux-gnu.2.17`, linked by zig against glibc 2.17 (the
//!   manylinux2014 baseline: RHEL 7 and every later distribution).
//!   cargo-zigbuild and zig come from the pinned wheels in `.venv`
//!   (`tools/cross-deps.sh`); without them the native build is packaged and
//!   a line says so.
//! - `binaries/win64/<model>.dll`: `x86_64-pc-windows-gnu`, linked by
//!   mingw-w64. Without that Rust target or `x86_64-w64-mingw32-gcc` the FMU
//!   has no win64 folder and a line says so.
//!
//! The native build (`target/release`) also makes the `run_direct` binary
//! (the Rust engine run directly, for the fmpy tests' comparisons) and
//! `libfmu_stepper.so` (the native stepping loop of python/rocking).

use std::env;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

mod c_runtime;
mod licences;
mod wheel;

use sha2::{Digest, Sha256};
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, DateTime, ZipWriter};

/// One FMU of the workspace: its cdylib crate and what the archive is named.
struct Model {
    /// Cargo package (a directory of the workspace root of the same name).
    package: &'static str,
    /// Library target name of the cdylib.
    lib: &'static str,
    /// `modelIdentifier`: the archive and binary names.
    identifier: &'static str,
    /// Binaries built with the native release library.
    bins: &'static [&'static str],
    /// Other packages built with the native release library: the hosts'
    /// helpers the Python package loads from target/release.
    companions: &'static [&'static str],
    /// The library exports FMI 3.0 too: also write `target/fmu/fmi3/<model>.fmu`.
    fmi3: bool,
}

const ROCKING_BLOCK: Model = Model {
    package: "fmu-rocking",
    lib: "fmu_rocking",
    identifier: "RockingBlock",
    bins: &["run_direct"],
    // the stepping loop python/rocking/stepper.py loads
    companions: &["fmu-stepper"],
    fmi3: true,
};

const SHEAR_FRAME: Model = Model {
    package: "fmu-shear-frame",
    lib: "fmu_shear_frame",
    identifier: "ShearFrame",
    bins: &[],
    companions: &[],
    fmi3: true,
};

const ROUND_BODY: Model = Model {
    package: "fmu-round-body",
    lib: "fmu_round_body",
    identifier: "RoundBody",
    bins: &[],
    companions: &[],
    fmi3: true,
};

/// The FMUs `cargo xtask fmu` writes.
const MODELS: [&Model; 3] = [&ROCKING_BLOCK, &SHEAR_FRAME, &ROUND_BODY];

/// The model of the cross-check artefacts.
const MODEL_IDENTIFIER: &str = ROCKING_BLOCK.identifier;

type Res<T> = Result<T, String>;

/// `--force`: write every archive even where its stamp says it is up to date.
static FORCE: AtomicBool = AtomicBool::new(false);

fn main() {
    let mut args: Vec<String> = env::args().skip(1).collect();
    if args.first().is_some_and(|a| a != "wheel" && a != "bundle") {
        let before = args.len();
        args.retain(|a| a != "--force");
        FORCE.store(args.len() != before, Ordering::Relaxed);
    }
    let result = match args.first().map(String::as_str) {
        Some("fmu") => MODELS.iter().try_for_each(|m| package(m).map(|_| ())),
        Some("rocking-block") => package(&ROCKING_BLOCK).map(|_| ()),
        Some("shear-frame") => package(&SHEAR_FRAME).map(|_| ()),
        Some("round-body") => package(&ROUND_BODY).map(|_| ()),
        Some("crosscheck") => crosscheck(),
        Some("wheel") => wheel::wheels(&args[1..]),
        Some("bundle") => wheel::bundle(&args[1..]),
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
         fmu            build the release libraries for linux64 (glibc 2.17) and win64 and write\n                 \
         target/fmu/RockingBlock.fmu, target/fmu/ShearFrame.fmu,\n                 \
         target/fmu/RoundBody.fmu (and\n                 \
         target/release/run_direct, target/release/libfmu_stepper.so); an archive\n                 \
         whose entries and writer did not change is left as it is (--force: write it)\n  \
         rocking-block  only target/fmu/RockingBlock.fmu (and run_direct, libfmu_stepper.so)\n  \
         shear-frame    only target/fmu/ShearFrame.fmu\n  \
         round-body     only target/fmu/RoundBody.fmu\n  \
         crosscheck     the FMUs, then RockingBlock's FMI cross-check artefacts (FMU, input,\n                 \
         reference results from the engine run directly, options, README) under\n                 \
         target/cross-check/fmus/2.0/cs/{{linux64,win64}}/...\n  \
         wheel          the Python package's wheels (manylinux2014 x86_64, win_amd64) carrying\n                 \
         both FMUs, the stepping loop, rocking-corner and sample records, and its sdist,\n                 \
         in target/wheels (--reuse-fmus: take target/fmu/*.fmu as they are)\n  \
         bundle DIR     the FMUs, the stepping loop and rocking-corner for this machine, and the\n                 \
         sample records into DIR (a wheel's rocking/_bundled: setup.py, from the sdist)"
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

/// Runs a cargo build (`--message-format=json-render-diagnostics`) and
/// returns its JSON messages about the model's package.
fn cargo_messages(cmd: Command, model: &Model) -> Res<Vec<serde_json::Value>> {
    let fmu_dir = root().join(model.package);
    Ok(all_messages(cmd)?
        .into_iter()
        .filter(|v| {
            package_dir(v["package_id"].as_str().unwrap_or("")).is_some_and(|d| d == fmu_dir)
        })
        .collect())
}

/// Runs a cargo build (`--message-format=json-render-diagnostics`) and
/// returns all its JSON messages.
fn all_messages(mut cmd: Command) -> Res<Vec<serde_json::Value>> {
    let output = cmd
        .current_dir(root())
        .arg("--message-format=json-render-diagnostics")
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot run {:?}: {e}", cmd.get_program()))?;
    if !output.status.success() {
        return Err(format!(
            "{:?} build failed ({})",
            cmd.get_program(),
            output.status
        ));
    }
    Ok(String::from_utf8_lossy(&output.stdout)
        .lines()
        .filter_map(|line| serde_json::from_str::<serde_json::Value>(line).ok())
        .collect())
}

/// The model's cdylib among the messages, the file ending in `suffix`.
fn cdylib(messages: &[serde_json::Value], model: &Model, suffix: &str) -> Option<PathBuf> {
    messages.iter().find_map(|v| {
        let kinds = v["target"]["kind"].as_array()?;
        if v["reason"] != "compiler-artifact"
            || v["target"]["name"] != model.lib
            || !kinds.iter().any(|k| k == "cdylib")
        {
            return None;
        }
        v["filenames"]
            .as_array()?
            .iter()
            .filter_map(|x| x.as_str())
            .find(|x| x.ends_with(suffix))
            .map(PathBuf::from)
    })
}

fn cargo() -> Command {
    Command::new(env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
}

/// The native release build: the library the tests load from
/// `target/release`, the XML and page of its build script, and `run_direct`.
fn build(model: &Model) -> Res<Built> {
    let mut cmd = cargo();
    cmd.args(["build", "--release", "--package", model.package, "--lib"]);
    for p in model.companions {
        cmd.args(["--package", p]);
    }
    for b in model.bins {
        cmd.args(["--bin", b]);
    }
    let messages = cargo_messages(cmd, model)?;
    let out_dir = messages
        .iter()
        .filter(|v| v["reason"] == "build-script-executed")
        .find_map(|v| v["out_dir"].as_str().map(PathBuf::from));
    let run_direct = messages
        .iter()
        .filter(|v| v["reason"] == "compiler-artifact" && v["target"]["name"] == "run_direct")
        .find_map(|v| v["executable"].as_str().map(PathBuf::from));
    Ok(Built {
        library: cdylib(&messages, model, ".so")
            .ok_or_else(|| format!("cargo reported no {} cdylib", model.lib))?,
        out_dir: out_dir.ok_or_else(|| {
            format!(
                "cargo reported no build-script output for {}",
                model.package
            )
        })?,
        run_direct,
    })
}

/// Whether `program --version` runs.
fn runs(program: &Path) -> bool {
    Command::new(program)
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// The glibc baseline of the linux64 binary (manylinux2014).
const LINUX64_TARGET: &str = "x86_64-unknown-linux-gnu.2.17";
const WIN64_TARGET: &str = "x86_64-pc-windows-gnu";
const MINGW_GCC: &str = "x86_64-w64-mingw32-gcc";

/// The linux64 library linked against glibc 2.17 by cargo-zigbuild, or
/// `Err(why not)` when cargo-zigbuild is missing.
fn build_linux64(model: &Model) -> Res<Result<PathBuf, String>> {
    build_with(linux64_cargo()?, model, LINUX64_TARGET, "linux64", ".so")
}

/// [`build_platform`] with the platform's cargo, or `Err(why not)` when there is none.
fn build_with(
    cargo: Result<Command, String>,
    model: &Model,
    target: &str,
    platform: &str,
    extension: &str,
) -> Res<Result<PathBuf, String>> {
    match cargo {
        Ok(cmd) => Ok(Ok(build_platform(cmd, model, target, platform, extension)?)),
        Err(why) => Ok(Err(why)),
    }
}

/// `cargo zigbuild` of .venv (or PATH) with its zig, or `Err(why not)`.
fn linux64_cargo() -> Res<Result<Command, String>> {
    let venv_bin = root().join(".venv/bin");
    let zigbuild = [venv_bin.join("cargo-zigbuild"), "cargo-zigbuild".into()]
        .into_iter()
        .find(|p| runs(p));
    let Some(zigbuild) = zigbuild else {
        return Ok(Err(
            "cargo-zigbuild not found in .venv or on PATH (tools/cross-deps.sh installs it)".into(),
        ));
    };
    let mut cmd = Command::new(zigbuild);
    // cargo-zigbuild finds zig as CARGO_ZIGBUILD_ZIG_PATH, `zig` on PATH or
    // `python3 -m ziglang`: point it at the ziglang wheel of .venv
    let python_zig = venv_bin.join("python-zig");
    if env::var_os("CARGO_ZIGBUILD_ZIG_PATH").is_none() && python_zig.is_file() {
        cmd.env("CARGO_ZIGBUILD_ZIG_PATH", &python_zig);
    }
    let path = env::var_os("PATH").unwrap_or_default();
    let mut paths = vec![venv_bin];
    paths.extend(env::split_paths(&path));
    cmd.env(
        "PATH",
        env::join_paths(paths).map_err(|e| format!("PATH: {e}"))?,
    );
    Ok(Ok(cmd))
}

/// Runs `cmd` (cargo or cargo zigbuild) to build the FMU's cdylib for
/// `target` in its own target dir `platforms/<platform>`, and returns the
/// library (ending in `extension`).
fn build_platform(
    mut cmd: Command,
    model: &Model,
    target: &str,
    platform: &str,
    extension: &str,
) -> Res<PathBuf> {
    cmd.args([
        "build",
        "--release",
        "--package",
        model.package,
        "--lib",
        "--target",
        target,
        "--target-dir",
    ]);
    cmd.arg(target_dir().join("platforms").join(platform));
    shipped_profile(&mut cmd);
    if platform == "win64" {
        // a DLL's exports are its export table: the COFF symbol table
        // (5715 symbols) is only a debugger's, and no Windows user has ours
        cmd.env("CARGO_PROFILE_RELEASE_STRIP", "symbols");
    }
    let messages = cargo_messages(cmd, model)?;
    cdylib(&messages, model, extension)
        .ok_or_else(|| format!("cargo reported no {} {extension} for {target}", model.lib))
}

/// The shipped binary carries its symbols but no debug information: a
/// fifth of the size, and compressing the 5.5 MB of DWARF was 3.1 of the
/// packaging's 3.3 s. The native build of target/release keeps it (the
/// profile's `debug = 1`) for profilers and debuggers.
fn shipped_profile(cmd: &mut Command) {
    cmd.env("CARGO_PROFILE_RELEASE_DEBUG", "0")
        .env("CARGO_PROFILE_RELEASE_STRIP", "debuginfo");
}

/// The win64 DLL, or `Err(why not)` when the Rust target or mingw-w64 is missing.
fn build_win64(model: &Model) -> Res<Result<PathBuf, String>> {
    build_with(win64_cargo()?, model, WIN64_TARGET, "win64", ".dll")
}

/// cargo set up to link for win64 with mingw-w64, or `Err(why not)` when the
/// Rust target or mingw-w64 is missing.
fn win64_cargo() -> Res<Result<Command, String>> {
    let sysroot = Command::new(env::var("RUSTC").unwrap_or_else(|_| "rustc".into()))
        .args(["--print", "sysroot"])
        .output()
        .map_err(|e| format!("rustc --print sysroot: {e}"))?;
    let sysroot = PathBuf::from(String::from_utf8_lossy(&sysroot.stdout).trim());
    if !sysroot.join("lib/rustlib").join(WIN64_TARGET).is_dir() {
        return Ok(Err(format!(
            "the Rust target {WIN64_TARGET} is not installed \
             (rustup target add {WIN64_TARGET}; tools/cross-deps.sh does it)"
        )));
    }
    if !runs(Path::new(MINGW_GCC)) {
        return Ok(Err(format!(
            "{MINGW_GCC} not found (Debian: gcc-mingw-w64-x86-64; tools/cross-deps.sh installs it)"
        )));
    }
    let mut cmd = cargo();
    // GNU ld writes the link time into the PE header unless told not to:
    // without it, the archive would differ at every build
    cmd.env(
        "CARGO_TARGET_X86_64_PC_WINDOWS_GNU_RUSTFLAGS",
        "-C link-arg=-Wl,--no-insert-timestamp",
    );
    Ok(Ok(cmd))
}

fn read(p: &Path) -> Res<Vec<u8>> {
    fs::read(p).map_err(|e| format!("{}: {e}", p.display()))
}

fn contains(haystack: &[u8], needle: &[u8]) -> bool {
    haystack.windows(needle.len()).any(|w| w == needle)
}

/// Writes the archive: sorted entries, fixed time stamps and permissions.
/// Returns false when the archive was left as it is: its stamp says it was
/// written by this very xtask binary from the same entries, and it is still
/// the file that was written then (`--force` writes it anyway).
fn write_fmu(path: &Path, entries: &mut [(String, Vec<u8>, u32)]) -> Res<bool> {
    write_archive(
        path,
        &stamp_path(path),
        entries,
        FORCE.load(Ordering::Relaxed),
    )
}

/// [`write_fmu`] with its stamp file given.
fn write_archive(
    path: &Path,
    stamp: &Path,
    entries: &mut [(String, Vec<u8>, u32)],
    force: bool,
) -> Res<bool> {
    entries.sort_by(|a, b| a.0.cmp(&b.0));
    let inputs = inputs_digest(entries)?;
    if !force && up_to_date(path, stamp, &inputs) {
        return Ok(false);
    }
    // a name of this process's own: two packagings at once (two shells, a
    // test beside the main job) would otherwise rename each other's file
    let tmp = path.with_extension(format!("fmu.{}.tmp", std::process::id()));
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
    fs::rename(&tmp, path).map_err(|e| format!("{}: {e}", path.display()))?;
    // the stamp last: an archive written without one is written again next time
    let written = hex(&Sha256::digest(read(path)?));
    if let Some(dir) = stamp.parent() {
        fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    fs::write(stamp, format!("inputs {inputs}\narchive {written}\n"))
        .map_err(|e| format!("{}: {e}", stamp.display()))?;
    Ok(true)
}

/// Where `write_fmu` records what an archive under the target directory was
/// written from: `target/xtask-stamps/<the archive's path under target>.sha256`
/// (outside the target directory: beside the archive).
fn stamp_path(archive: &Path) -> PathBuf {
    let target = target_dir();
    let (dir, rel) = match archive.strip_prefix(&target) {
        Ok(rel) => (target.join("xtask-stamps"), rel),
        Err(_) => (PathBuf::new(), archive),
    };
    let mut name = rel.as_os_str().to_os_string();
    name.push(".sha256");
    dir.join(name)
}

/// SHA-256 of what decides an archive's bytes: the writer (this executable:
/// its zip and deflate code, the options above) and every entry's name,
/// mode and bytes, in the archive's order. The executable is named by its
/// path, size and modification time rather than its bytes (tens of MB in
/// the debug build `cargo xtask` runs): cargo relinks it on any change.
fn inputs_digest(entries: &[(String, Vec<u8>, u32)]) -> Res<String> {
    let exe = env::current_exe().map_err(|e| format!("the xtask executable: {e}"))?;
    let meta = fs::metadata(&exe).map_err(|e| format!("{}: {e}", exe.display()))?;
    let modified = meta
        .modified()
        .ok()
        .and_then(|t| t.duration_since(std::time::UNIX_EPOCH).ok())
        .map_or(0, |d| d.as_nanos());
    let mut h = Sha256::new();
    h.update(format!("{} {} {modified}\n", exe.display(), meta.len()).as_bytes());
    for (name, data, mode) in entries {
        h.update((name.len() as u64).to_le_bytes());
        h.update(name.as_bytes());
        h.update(mode.to_le_bytes());
        h.update((data.len() as u64).to_le_bytes());
        h.update(data);
    }
    Ok(hex(&h.finalize()))
}

/// Whether `stamp` names these `inputs` and the archive's present bytes.
fn up_to_date(archive: &Path, stamp: &Path, inputs: &str) -> bool {
    let Ok(text) = fs::read_to_string(stamp) else {
        return false;
    };
    let mut lines = text.lines();
    if lines.next() != Some(&format!("inputs {inputs}")) {
        return false;
    }
    let Ok(bytes) = fs::read(archive) else {
        return false;
    };
    lines.next() == Some(&format!("archive {}", hex(&Sha256::digest(bytes))))
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Builds and packages; returns the archive, the native build's products
/// and the platforms the archive has binaries for.
fn package(model: &Model) -> Res<(PathBuf, Built, Vec<&'static str>)> {
    let what = format!("{}.fmu", model.identifier);
    // the four cargo runs at once: each platform builds in a target
    // directory of its own, and when nothing changed each is mostly cargo's
    // and zig's start-up (1.9 of a warm packaging's 2.4 s one after another)
    let (built, licence, linux64, win64) = std::thread::scope(|s| {
        let timed = |f: fn(&Model) -> Res<Result<PathBuf, String>>| {
            move || {
                let start = Instant::now();
                f(model).map(|r| (r, start.elapsed().as_secs_f64()))
            }
        };
        let linux64 = s.spawn(timed(build_linux64));
        let win64 = s.spawn(timed(build_win64));
        let licence = s.spawn(|| licences::file(&[model.package], &what));
        let built = build(model);
        let join = |what: &str| format!("the {what} build panicked");
        (
            built,
            licence
                .join()
                .map_err(|_| join("licence file's"))
                .and_then(|r| r),
            linux64.join().map_err(|_| join("linux64")).and_then(|r| r),
            win64.join().map_err(|_| join("win64")).and_then(|r| r),
        )
    });
    let built = built?;
    let xml = read(&built.out_dir.join("modelDescription.xml"))?;
    let guid = String::from_utf8(read(&built.out_dir.join("guid.txt"))?)
        .map_err(|e| format!("guid.txt: {e}"))?;
    let html = read(&built.out_dir.join("index.html"))?;
    if !contains(&xml, format!("guid=\"{guid}\"").as_bytes()) {
        return Err(format!(
            "modelDescription.xml does not carry the GUID {guid}"
        ));
    }
    let mut entries = vec![
        ("modelDescription.xml".to_string(), xml, 0o644),
        ("documentation/index.html".to_string(), html, 0o644),
    ];
    let xml3 = read(&built.out_dir.join("modelDescription3.xml"))?;
    let mut entries3 = vec![
        ("modelDescription.xml".to_string(), xml3, 0o644),
        (
            "documentation/index.html".to_string(),
            entries[1].1.clone(),
            0o644,
        ),
    ];
    let mut licence = licence?;
    let mut platforms = Vec::new();
    let mut add = |platform: &'static str, library: &Path, seconds: f64| -> Res<()> {
        let data = read(library)?;
        if !contains(&data, guid.as_bytes()) {
            return Err(format!(
                "{} does not embed the GUID {guid} of the generated modelDescription.xml",
                library.display()
            ));
        }
        let ext = library.extension().and_then(|e| e.to_str()).unwrap_or("");
        let name = format!("binaries/{platform}/{}.{ext}", model.identifier);
        println!(
            "{name}: {} bytes, built in {seconds:.1} s ({})",
            data.len(),
            library.display()
        );
        let name3 = format!(
            "binaries/{}/{}.{ext}",
            fmi3_platform(platform),
            model.identifier
        );
        entries3.push((name3, data.clone(), 0o755));
        entries.push((name, data, 0o755));
        platforms.push(platform);
        Ok(())
    };
    match linux64? {
        (Ok(so), seconds) => add("linux64", &so, seconds)?,
        (Err(why), _) => {
            println!(
                "linux64: {why}: packaging the native build, linked against this machine's glibc"
            );
            add("linux64", &built.library, 0.0)?;
        }
    }
    match win64? {
        // a binary whose C runtime's notice cannot be found is not shipped
        // (a machine with mingw-w64 but no dpkg, building from the sdist)
        (Ok(dll), seconds) => match c_runtime::section() {
            Ok(notice) => {
                add("win64", &dll, seconds)?;
                licence.push_str(&notice);
            }
            Err(why) => println!("win64: skipped: the licence of its C runtime: {why}"),
        },
        (Err(why), _) => println!("win64: skipped: {why}"),
    }
    entries.push((
        licences::FMU_ENTRY.into(),
        licence.clone().into_bytes(),
        0o644,
    ));
    entries3.push((licences::FMU_ENTRY.into(), licence.into_bytes(), 0o644));
    let dir = target_dir().join("fmu");
    fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let path = dir.join(format!("{}.fmu", model.identifier));
    let status = |written| if written { "" } else { ", unchanged" };
    let written = write_fmu(&path, &mut entries)?;
    let size = fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
    println!(
        "{} ({size} bytes, GUID {guid}{})",
        path.display(),
        status(written)
    );
    if model.fmi3 {
        let dir3 = dir.join("fmi3");
        fs::create_dir_all(&dir3).map_err(|e| format!("{}: {e}", dir3.display()))?;
        let path3 = dir3.join(format!("{}.fmu", model.identifier));
        let written = write_fmu(&path3, &mut entries3)?;
        let size = fs::metadata(&path3).map(|m| m.len()).unwrap_or(0);
        println!(
            "{} (FMI 3.0, {size} bytes, token {guid}{})",
            path3.display(),
            status(written)
        );
    }
    if let Some(r) = &built.run_direct {
        println!("{}", r.display());
    }
    Ok((path, built, platforms))
}

/// FMI 3.0's name of an FMI 2.0 platform folder (`<arch>-<os>`).
fn fmi3_platform(platform: &str) -> &'static str {
    match platform {
        "linux64" => "x86_64-linux",
        "win64" => "x86_64-windows",
        other => panic!("no FMI 3.0 name for platform {other}"),
    }
}

/// The cross-check case: the default block on its crushing joint under a
/// decaying 1.5 Hz ground motion, sampled on the communication grid.
const CC_STEP: f64 = 0.01;
const CC_STOP: f64 = 10.0;
const CC_RELTOL: f64 = 1e-9;

fn cc_ground_motion(t: f64) -> f64 {
    3.0 * (2.0 * std::f64::consts::PI * 1.5 * t).sin() * (-0.3 * t).exp()
}

/// `cargo xtask crosscheck`: both FMUs, and FMI cross-check artefacts for RockingBlock.
fn crosscheck() -> Res<()> {
    // every FMU, as `cargo xtask fmu` (the test command runs this task only)
    package(&SHEAR_FRAME)?;
    package(&ROUND_BODY)?;
    let (fmu_path, built, platforms) = package(&ROCKING_BLOCK)?;
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
    // the same artefacts for every other platform of the archive: the
    // reference is the engine's, whatever the platform
    for platform in platforms.iter().filter(|&&p| p != "linux64") {
        let other = target_dir()
            .join("cross-check/fmus/2.0/cs")
            .join(platform)
            .join(MODEL_IDENTIFIER)
            .join(version)
            .join(MODEL_IDENTIFIER);
        fs::create_dir_all(&other).map_err(|e| format!("{}: {e}", other.display()))?;
        for entry in fs::read_dir(&dir).map_err(|e| format!("{}: {e}", dir.display()))? {
            let from = entry.map_err(|e| format!("{}: {e}", dir.display()))?.path();
            let to = other.join(from.file_name().unwrap_or_default());
            fs::copy(&from, &to).map_err(|e| format!("{}: {e}", to.display()))?;
        }
        println!("{}", other.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entries(doc: &[u8]) -> Vec<(String, Vec<u8>, u32)> {
        vec![
            (
                "modelDescription.xml".into(),
                b"<fmiModelDescription/>".to_vec(),
                0o644,
            ),
            ("documentation/index.html".into(), doc.to_vec(), 0o644),
            ("binaries/linux64/M.so".into(), vec![7; 100_000], 0o755),
        ]
    }

    /// A scratch folder of this test's own under the target directory.
    fn scratch(name: &str) -> PathBuf {
        let dir = target_dir().join("xtask-test").join(name);
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn an_archive_is_written_again_exactly_when_its_inputs_or_bytes_change() {
        let dir = scratch("stamps");
        let (fmu, stamp) = (dir.join("M.fmu"), dir.join("M.fmu.sha256"));
        // a full write elsewhere: the bytes every later state must equal
        let fresh = |doc: &[u8], name: &str| {
            let p = dir.join(name);
            assert!(write_archive(&p, &dir.join("x.sha256"), &mut entries(doc), true).unwrap());
            fs::read(p).unwrap()
        };
        assert!(write_archive(&fmu, &stamp, &mut entries(b"a"), false).unwrap());
        assert_eq!(fs::read(&fmu).unwrap(), fresh(b"a", "a.fmu"));
        // the same entries, in another order: left as it is
        let mut shuffled = entries(b"a");
        shuffled.reverse();
        assert!(!write_archive(&fmu, &stamp, &mut shuffled, false).unwrap());
        assert_eq!(fs::read(&fmu).unwrap(), fresh(b"a", "a2.fmu"));
        // one entry's bytes changed: written, equal to a full write
        assert!(write_archive(&fmu, &stamp, &mut entries(b"b"), false).unwrap());
        assert_eq!(fs::read(&fmu).unwrap(), fresh(b"b", "b.fmu"));
        // a mode changed
        let mut exec = entries(b"b");
        exec[1].2 = 0o755;
        assert!(write_archive(&fmu, &stamp, &mut exec, false).unwrap());
        assert!(write_archive(&fmu, &stamp, &mut entries(b"b"), false).unwrap());
        // the archive altered behind the stamp's back: written again
        let mut bytes = fs::read(&fmu).unwrap();
        bytes.push(0);
        fs::write(&fmu, bytes).unwrap();
        assert!(write_archive(&fmu, &stamp, &mut entries(b"b"), false).unwrap());
        assert_eq!(fs::read(&fmu).unwrap(), fresh(b"b", "b2.fmu"));
        // the archive gone, or the stamp: written again
        fs::remove_file(&fmu).unwrap();
        assert!(write_archive(&fmu, &stamp, &mut entries(b"b"), false).unwrap());
        fs::remove_file(&stamp).unwrap();
        assert!(write_archive(&fmu, &stamp, &mut entries(b"b"), false).unwrap());
        assert!(!write_archive(&fmu, &stamp, &mut entries(b"b"), false).unwrap());
        // forced: written, the same bytes
        assert!(write_archive(&fmu, &stamp, &mut entries(b"b"), true).unwrap());
        assert_eq!(fs::read(&fmu).unwrap(), fresh(b"b", "b3.fmu"));
    }

    #[test]
    fn the_stamps_of_the_archives_live_under_the_target_directory() {
        let t = target_dir();
        assert_eq!(
            stamp_path(&t.join("fmu/fmi3/M.fmu")),
            t.join("xtask-stamps/fmu/fmi3/M.fmu.sha256")
        );
        assert_eq!(
            stamp_path(Path::new("/elsewhere/M.fmu")),
            PathBuf::from("/elsewhere/M.fmu.sha256")
        );
    }
}
