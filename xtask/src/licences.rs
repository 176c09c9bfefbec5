//! The licence file of a shipped artefact (an FMU, a wheel): every crate
//! compiled into its binaries, with its licence expression and the licence
//! texts the crate ships, read from Cargo's metadata.
//!
//! Written here rather than by cargo-about (docs/decisions.md, "The
//! third-party licence file"): cargo-about would be a `cargo install` of a
//! few hundred crates in every fresh clone's main job and test command, for
//! what `cargo metadata` and the crates' own folders already hold; the one
//! thing it adds, SPDX's canonical text for a crate that ships none, is
//! refused here instead (every crate in the graph ships its texts today).

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

use crate::{root, Res, LINUX64_TARGET, WIN64_TARGET};

/// The Rust targets of the shipped binaries (linux64 without its glibc suffix).
fn targets() -> [&'static str; 2] {
    let linux = LINUX64_TARGET
        .strip_suffix(".2.17")
        .expect("the linux64 target carries its glibc version");
    [linux, WIN64_TARGET]
}

/// Where the file goes in an FMU: FMI 3.0's folder for licences
/// (`documentation/licenses`, with `license.txt` as its entry point), used in
/// the 2.0 archive too.
pub const FMU_ENTRY: &str = "documentation/licenses/license.txt";

/// One crate of the graph.
struct Crate {
    name: String,
    version: String,
    expression: String,
    /// (file name, text), sorted by name.
    texts: Vec<(String, String)>,
}

/// The licence file of the binaries built from the workspace packages
/// `roots`, for both shipped targets; `what` names the artefact in its title.
pub fn file(roots: &[&str], what: &str) -> Res<String> {
    let crates = graph(roots)?;
    Ok(render(&crates, roots, what))
}

/// The crates the `roots` depend on through normal dependencies for the
/// shipped targets (the roots included), as `cargo tree` resolves them:
/// features per build, as the shipped build resolves them (`cargo
/// metadata`'s graph unifies them over the whole workspace, and named 17
/// crates that RockingBlock's library does not link, such as sha2, which
/// only its build script's model-description uses). Build scripts'
/// dependencies are left out: no code of theirs is in a binary. Procedural
/// macros (and what they depend on) are kept, since the code they write is.
/// `cargo metadata` gives each crate's licence expression and folder.
fn graph(roots: &[&str]) -> Res<Vec<Crate>> {
    let mut wanted = BTreeSet::new();
    for target in targets() {
        let mut cmd = crate::cargo();
        cmd.current_dir(root()).args([
            "tree", "--locked", "--edges", "normal", "--prefix", "none", "--format", "{p}",
            "--target", target,
        ]);
        for name in roots {
            cmd.args(["--package", name]);
        }
        let out = run(cmd, "cargo tree")?;
        for line in String::from_utf8_lossy(&out).lines() {
            // `name vX.Y.Z`, then ` (path)`, ` (proc-macro)`, ` (*)`
            let mut words = line.split_whitespace();
            if let (Some(name), Some(version)) = (words.next(), words.next()) {
                let version = version.strip_prefix('v').unwrap_or(version);
                wanted.insert((name.to_string(), version.to_string()));
            }
        }
    }
    let mut cmd = crate::cargo();
    cmd.current_dir(root())
        .args(["metadata", "--format-version", "1", "--locked"]);
    for target in targets() {
        cmd.args(["--filter-platform", target]);
    }
    let meta: serde_json::Value = serde_json::from_slice(&run(cmd, "cargo metadata")?)
        .map_err(|e| format!("cargo metadata: {e}"))?;
    let members: BTreeSet<&str> = meta["workspace_members"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|m| m.as_str())
        .collect();
    let mut crates = Vec::new();
    for package in meta["packages"].as_array().into_iter().flatten() {
        let key = (
            package["name"].as_str().unwrap_or("").to_string(),
            package["version"].as_str().unwrap_or("").to_string(),
        );
        if wanted.remove(&key) {
            let member = members.contains(package["id"].as_str().unwrap_or(""));
            crates.push(describe(package, member)?);
        }
    }
    if !wanted.is_empty() {
        return Err(format!(
            "licences: cargo tree names crates cargo metadata does not: {wanted:?}"
        ));
    }
    crates.sort_by(|a, b| (&a.name, &a.version).cmp(&(&b.name, &b.version)));
    Ok(crates)
}

/// Runs a cargo command in the workspace; its standard output.
fn run(mut cmd: std::process::Command, what: &str) -> Res<Vec<u8>> {
    let out = cmd
        .output()
        .map_err(|e| format!("cannot run {what}: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "{what} failed: {}",
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    Ok(out.stdout)
}

/// A crate's name, version, licence expression and texts: the files of its
/// folder named LICENSE*, LICENCE*, COPYING*, COPYRIGHT*, NOTICE*, UNLICENSE*,
/// those of a LICENSES/ folder, and its `license-file`; the workspace's own
/// crates without such files carry the workspace root's.
fn describe(package: &serde_json::Value, member: bool) -> Res<Crate> {
    let field = |key: &str| package[key].as_str().unwrap_or("").to_string();
    let (name, version) = (field("name"), field("version"));
    let manifest = PathBuf::from(field("manifest_path"));
    let dir = manifest.parent().unwrap_or(Path::new("."));
    let mut files: BTreeSet<PathBuf> = licence_files(dir)?;
    if let Some(extra) = package["license_file"].as_str() {
        files.insert(dir.join(extra));
    }
    if files.is_empty() && member {
        files = licence_files(&root())?;
    }
    let mut expression = field("license");
    if expression.is_empty() {
        expression = "(no SPDX expression: see its licence file)".into();
    }
    let mut texts = Vec::new();
    if files.is_empty() {
        // a package without its texts (argmin, argmin-math): where its
        // expression offers Apache-2.0, that licence's text (which names no
        // copyright holder) is the workspace's own LICENSE-APACHE
        let offers_apache = expression
            .split(" OR ")
            .any(|alt| alt.trim_matches(|c| c == '(' || c == ')').trim() == "Apache-2.0");
        if !offers_apache {
            return Err(format!(
                "licences: {name} {version} ({}) ships no licence file and its licence \
                 {expression:?} offers no Apache-2.0 whose text the project carries",
                dir.display()
            ));
        }
        let authors: Vec<&str> = package["authors"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|a| a.as_str())
            .collect();
        expression = format!(
            "{expression}, taken as Apache-2.0 (authors: {}; the package ships no licence file)",
            authors.join(", ")
        );
        let apache = root().join("LICENSE-APACHE");
        let text = fs::read_to_string(&apache).map_err(|e| format!("{}: {e}", apache.display()))?;
        texts.push(("Apache-2.0".to_string(), text.trim_end().to_string()));
    }
    texts.extend(
        files
            .iter()
            .map(|f| {
                let text = fs::read(f).map_err(|e| format!("{}: {e}", f.display()))?;
                let shown = f.strip_prefix(dir).unwrap_or(f).display().to_string();
                Ok((shown, String::from_utf8_lossy(&text).trim_end().to_string()))
            })
            .collect::<Res<Vec<_>>>()?,
    );
    Ok(Crate {
        name,
        version,
        expression,
        texts,
    })
}

fn is_licence_name(name: &str) -> bool {
    let upper = name.to_ascii_uppercase();
    [
        "LICENSE",
        "LICENCE",
        "COPYING",
        "COPYRIGHT",
        "NOTICE",
        "UNLICENSE",
    ]
    .iter()
    .any(|p| upper.starts_with(p))
}

/// The licence files of a folder, and those of its LICENSES/ subfolder.
fn licence_files(dir: &Path) -> Res<BTreeSet<PathBuf>> {
    let mut found = BTreeSet::new();
    let entries = fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for entry in entries {
        let path = entry.map_err(|e| format!("{}: {e}", dir.display()))?.path();
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if path.is_file() && is_licence_name(name) {
            found.insert(path);
        } else if path.is_dir() && name.eq_ignore_ascii_case("LICENSES") {
            for sub in fs::read_dir(&path).map_err(|e| format!("{}: {e}", path.display()))? {
                let sub = sub.map_err(|e| format!("{}: {e}", path.display()))?.path();
                if sub.is_file() {
                    found.insert(sub);
                }
            }
        }
    }
    Ok(found)
}

/// The file: a list of crates, each naming the texts it ships, then each
/// distinct text once with the crates (and their file names) that ship it.
fn render(crates: &[Crate], roots: &[&str], what: &str) -> String {
    // text -> (its number, the crates and file names that carry it)
    let mut texts: Vec<(&str, Vec<String>)> = Vec::new();
    let mut numbers: Vec<Vec<usize>> = Vec::new();
    for c in crates {
        let mut own = Vec::new();
        for (file, text) in &c.texts {
            let who = format!("{} {} ({file})", c.name, c.version);
            let k = match texts.iter().position(|(t, _)| t == text) {
                Some(k) => k,
                None => {
                    texts.push((text, Vec::new()));
                    texts.len() - 1
                }
            };
            texts[k].1.push(who);
            if !own.contains(&(k + 1)) {
                own.push(k + 1);
            }
        }
        numbers.push(own);
    }
    let [linux, windows] = targets();
    let mut out = format!(
        "Licences of the software compiled into {what}\n\n\
         Generated by `cargo xtask` from Cargo's metadata (`cargo tree`, `cargo metadata`, \
         Cargo.lock): the crates of {} and of everything they depend on for {linux} and \
         {windows} (normal dependencies, procedural macros included; build scripts' own \
         dependencies left out, as none of their code is in a binary; features resolved per \
         build), each with the licence expression of its Cargo.toml and the licence files its \
         package ships. The project's own crates are listed too (MIT OR Apache-2.0). Rust's \
         standard library, compiled into every binary, is under MIT OR Apache-2.0 as well \
         (the texts are those of the project's crates).\n\n\
         Crates ({}):\n",
        roots.join(", "),
        crates.len()
    );
    for (c, own) in crates.iter().zip(&numbers) {
        let list: Vec<String> = own.iter().map(usize::to_string).collect();
        out.push_str(&format!(
            "  {} {}: {} [texts {}]\n",
            c.name,
            c.version,
            c.expression,
            list.join(", ")
        ));
    }
    out.push_str(&format!("\nTexts ({}):\n", texts.len()));
    for (k, (text, who)) in texts.iter().enumerate() {
        out.push_str(&format!(
            "\n== Text {}: {}\n\n{text}\n",
            k + 1,
            who.join(", ")
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every crate of the wheels' graph ships a text (else `file` refuses),
    /// and a crate with no licence file of its own would be refused.
    #[test]
    fn the_shipped_graph_has_its_texts() {
        let text = file(
            &[
                "fmu-rocking",
                "fmu-shear-frame",
                "fmu-round-body",
                "fmu-stepper",
                "corner",
            ],
            "a test",
        )
        .expect("every shipped crate ships a licence text");
        assert!(text.contains("\n  nalgebra ") && text.contains("\n  clap "));
        // model-description's xml feature (quick-xml) is its build scripts' only
        assert!(!text.contains("\n  quick-xml "));
        let empty = std::env::temp_dir().join(format!("licences-test-{}", std::process::id()));
        fs::create_dir_all(&empty).unwrap();
        fs::write(empty.join("Cargo.toml"), "").unwrap();
        let package = |licence: &str| {
            serde_json::json!({"name": "x", "version": "1.0.0", "license": licence,
                "manifest_path": empty.join("Cargo.toml"), "authors": ["A. Person"]})
        };
        assert!(describe(&package("MIT"), false).is_err());
        let apache = describe(&package("MIT OR Apache-2.0"), false).unwrap();
        assert!(
            apache.texts[0].1.starts_with("Apache License")
                || apache.texts[0].1.contains("Apache License")
        );
        assert!(apache.expression.contains("A. Person"));
        fs::remove_dir_all(&empty).unwrap();
    }
}
