//! The library's layers are one-way: each top-level module of `src/` uses only modules of a
//! lower layer (and itself). The layers, bottom up:
//!
//! 0. `text`: how messages print numbers and quote input;
//! 1. `bytes`, `error`, `hash`, `limits`, `trig`: byte forms of saved states, typed errors, FNV
//!    hashes, the size caps of files and runs, `sin_cos` of the hot path;
//! 2. `beam` (the element and the mesh), `integrator` (one-step methods on any `DaeSystem`),
//!    `cosimulation` (the contract between a model and a co-simulation interface);
//! 3. `modal`: reference conditions, eigenproblem, mode selection, shape integrals;
//! 4. `rod`: the `RodBody` trait, the FFR rod, the segment chain, their cost model;
//! 5. `mechanism`: the slider-crank DAE, its start, stepping and outputs;
//! 6. `scene`: the TOML scene, composed of the layers' own spec types;
//! 7. `simulation`: the facade (a mechanism built from a scene, its state, snapshots);
//! 8. `drive` (crank laws and the run loop), `model` (the rod's model as a co-simulation
//!    model: the variable table, the input law between communication points, the hooks) and
//!    `crankshaft` (the second model), side by side;
//! 9. `fmi`: the FMU's C ABI, a generic FMI 2.0 / FMI 3.0 shell over any co-simulation model.
//!
//! The test reads every `.rs` file under `src/` (the binaries in `src/bin` excluded: they are
//! users of the library), collects each `crate::<module>` path (in `use` declarations and in
//! code), and fails on any use of a module in the same or a higher layer. On top of the order,
//! the FMI layer is a shell over any model: its files use only the contract `cosimulation` and
//! the utilities `bytes`, `error`, `hash`, `limits` and `text`, and name no model type; one
//! file, `src/fmi/registry.rs`, names the models it exports (`model`, `crankshaft`, and the
//! rod's `scene`) and instantiates them.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const LAYERS: &[(&str, usize)] = &[
    ("text", 0),
    ("bytes", 1),
    ("error", 1),
    ("hash", 1),
    ("limits", 1),
    ("trig", 1),
    ("beam", 2),
    ("integrator", 2),
    ("cosimulation", 2),
    ("modal", 3),
    ("rod", 4),
    ("mechanism", 5),
    ("scene", 6),
    ("simulation", 7),
    ("drive", 8),
    ("model", 8),
    ("crankshaft", 8),
    ("fmi", 9),
];

/// The modules the FMI shell may use: the co-simulation contract and the utilities.
const FMI_USES: &[&str] = &["cosimulation", "bytes", "error", "hash", "limits", "text"];

/// The one file of the shell that names the models, and what it may use besides.
const REGISTRY: &str = "fmi/registry.rs";
const REGISTRY_USES: &[&str] = &["model", "crankshaft", "scene"];

/// Types of the models, which no file of the shell but the registry names (also not through a
/// re-export).
const MODEL_TYPES: &[&str] = &[
    "RodModel",
    "CrankshaftModel",
    "CrankshaftScene",
    "Scene",
    "Simulation",
    "Inputs",
    "SavedModel",
    "VariableTable",
    "Mechanism",
];

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
    let mut shell = Vec::new();
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
        let relative = file.strip_prefix(&src).unwrap().display().to_string();
        if module == "fmi" {
            shell.extend(shell_violations(&relative, &text));
        }
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
    assert!(
        shell.is_empty(),
        "the FMI shell names models outside {REGISTRY}:\n{}",
        shell.join("\n")
    );
    assert!(
        violations.is_empty(),
        "uses against the layer order:\n{}",
        violations.join("\n")
    );
}

/// What a file of the FMI shell (`relative` to `src/`, its code `text`) uses that it may not.
fn shell_violations(relative: &str, text: &str) -> Vec<String> {
    let registry = relative == REGISTRY;
    let mut found = Vec::new();
    for used in used_modules(text) {
        let allowed = FMI_USES.contains(&used.as_str())
            || (registry && REGISTRY_USES.contains(&used.as_str()))
            || used == "fmi"
            || used == "self"
            || used == "super";
        if !allowed {
            found.push(format!("{relative} uses crate::{used}"));
        }
    }
    if !registry {
        // Words of code and strings ("Co-Simulation" is one word, not the type `Simulation`).
        let words: BTreeSet<&str> = text
            .split(|c: char| !(c.is_alphanumeric() || c == '_' || c == '-'))
            .collect();
        for name in MODEL_TYPES {
            if words.contains(name) {
                found.push(format!("{relative} names the model type {name}"));
            }
        }
    }
    found
}

#[test]
fn the_shell_check_sees_models_named_outside_the_registry() {
    assert!(shell_violations("fmi/instance/mod.rs", "use crate::cosimulation::X;").is_empty());
    assert_eq!(
        shell_violations("fmi/instance/mod.rs", "use crate::model::Thing;").len(),
        1
    );
    // A model type through a re-export of an allowed module is caught by its name.
    let v = shell_violations("fmi/resource.rs", "use super::registry::Scene;");
    assert_eq!(v, ["fmi/resource.rs names the model type Scene"]);
    assert!(shell_violations(REGISTRY, "use crate::model::RodModel;").is_empty());
    assert_eq!(
        shell_violations(REGISTRY, "use crate::mechanism::X;").len(),
        1
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
