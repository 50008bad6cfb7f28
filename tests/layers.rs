//! The library's layers are one-way: each top-level module of `src/` uses only modules of a
//! lower layer (and itself). The layers, bottom up:
//!
//! 0. `text`: how messages print numbers and quote input;
//! 1. `error`, `hash`, `limits`, `trig`: typed errors, FNV hashes, the size caps of files and
//!    runs, `sin_cos` of the hot path;
//! 2. `beam` (the element and the mesh), `integrator` (one-step methods on any `DaeSystem`);
//! 3. `modal`: reference conditions, eigenproblem, mode selection, shape integrals;
//! 4. `rod`: the `RodBody` trait, the FFR rod, the segment chain, their cost model;
//! 5. `mechanism`: the slider-crank DAE, its start, stepping and outputs;
//! 6. `scene`: the TOML scene, composed of the layers' own spec types;
//! 7. `simulation`: the facade (a mechanism built from a scene, its state, snapshots);
//! 8. `drive` (crank laws and the run loop) and `model` (the model's self-description: the
//!    variable table, the input law between communication points, the instance hooks), side
//!    by side;
//! 9. `fmi`: the FMU's C ABI, a generic FMI 2.0 / FMI 3.0 shell over `model`.
//!
//! The test reads every `.rs` file under `src/` (the binaries in `src/bin` excluded: they are
//! users of the library), collects each `crate::<module>` path (in `use` declarations and in
//! code), and fails on any use of a module in the same or a higher layer. On top of the order,
//! the FMI layer knows nothing of the mechanism: `fmi` uses only `model` and the utilities
//! `error`, `hash`, `limits` and `text`
//! (none of `mechanism`, `rod`, `modal`, `beam`, `integrator`, nor `scene` or `simulation`
//! except through `model`).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const LAYERS: &[(&str, usize)] = &[
    ("text", 0),
    ("error", 1),
    ("hash", 1),
    ("limits", 1),
    ("trig", 1),
    ("beam", 2),
    ("integrator", 2),
    ("modal", 3),
    ("rod", 4),
    ("mechanism", 5),
    ("scene", 6),
    ("simulation", 7),
    ("drive", 8),
    ("model", 8),
    ("fmi", 9),
];

/// The modules `fmi` may use: the model's self-description and layer 0.
const FMI_USES: &[&str] = &["model", "error", "hash", "limits", "text"];

/// The mechanism's modules, which `fmi` must not use.
const MECHANISM: &[&str] = &["mechanism", "rod", "modal", "beam", "integrator"];

fn layer(module: &str) -> Option<usize> {
    LAYERS.iter().find(|(m, _)| *m == module).map(|(_, l)| *l)
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            if path.file_name().unwrap() != "bin" {
                rust_files(&path, out);
            }
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The top-level modules a file names as `crate::<module>`, with `use crate::{a, b}` groups.
fn used_modules(text: &str) -> BTreeSet<String> {
    let mut used = BTreeSet::new();
    for (i, _) in text.match_indices("crate::") {
        let rest = &text[i + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            for item in group[..end].split(',') {
                let name: String = item
                    .trim()
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if !name.is_empty() {
                    used.insert(name);
                }
            }
        } else {
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            used.insert(name);
        }
    }
    used
}

/// The top-level module a file under `src/` belongs to (`src/rod/ffr/rod.rs` -> `rod`).
fn owner(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).unwrap();
    let first = rel.components().next()?.as_os_str().to_str()?.to_string();
    let name = first.trim_end_matches(".rs").to_string();
    (name != "lib").then_some(name)
}

#[test]
fn layers_are_one_way() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut violations = Vec::new();
    for file in &files {
        let Some(module) = owner(&src, file) else {
            continue;
        };
        let own = layer(&module).unwrap_or_else(|| {
            panic!("src module '{module}' has no layer: add it to LAYERS in tests/layers.rs")
        });
        // Code only: comments (and intra-doc links in them) are not dependencies.
        let text: String = std::fs::read_to_string(file)
            .unwrap()
            .lines()
            .map(|l| l.split("//").next().unwrap_or(""))
            .collect::<Vec<_>>()
            .join("\n");
        for used in used_modules(&text) {
            if used == module || used == "self" || used == "super" {
                continue;
            }
            let Some(theirs) = layer(&used) else {
                // Macros or items of lib.rs itself (e.g. `crate::Simulation`): resolve them.
                panic!(
                    "{}: `crate::{used}` is not a module path; name the module (crate::simulation::...)",
                    file.display()
                );
            };
            graph
                .entry(module.clone())
                .or_default()
                .insert(used.clone());
            if theirs >= own {
                violations.push(format!(
                    "{} ({module}, layer {own}) uses crate::{used} (layer {theirs})",
                    file.strip_prefix(&src).unwrap().display()
                ));
            }
        }
    }
    for (module, uses) in &graph {
        println!(
            "{module} -> {}",
            uses.iter().cloned().collect::<Vec<_>>().join(", ")
        );
    }
    let fmi_uses = graph.get("fmi").cloned().unwrap_or_default();
    let mechanism: Vec<&String> = fmi_uses
        .iter()
        .filter(|m| MECHANISM.contains(&m.as_str()))
        .collect();
    assert!(
        mechanism.is_empty(),
        "fmi uses the mechanism's modules {mechanism:?}: go through crate::model"
    );
    let other: Vec<&String> = fmi_uses
        .iter()
        .filter(|m| !FMI_USES.contains(&m.as_str()))
        .collect();
    assert!(
        other.is_empty(),
        "fmi uses {other:?}: allowed only {FMI_USES:?}"
    );
    assert!(
        fmi_uses.contains("model"),
        "fmi is the shell over crate::model: {fmi_uses:?}"
    );
    assert!(
        violations.is_empty(),
        "uses against the layer order:\n{}",
        violations.join("\n")
    );
}

#[test]
fn the_parser_sees_groups_and_paths() {
    let used = used_modules(
        "use crate::{beam::X, modal};\nfn f() { crate::rod::build(); }\nuse crate::error::E;",
    );
    let expected: BTreeSet<String> = ["beam", "modal", "rod", "error"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    assert_eq!(used, expected);
}
