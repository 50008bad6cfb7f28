//! What the printed summary of a scene may and must say (`flexrod simulate`, `flexrod modes`,
//! the packager's `--simulate`): the scene's own words, the strings a user writes in a scene
//! file (`ffr`, `simply_supported`, `consistent`), never the Rust names of the code (`Ffr`,
//! `SimplySupported`: a `Debug` print). fmu/tests/cli.rs includes this file by its path.

use std::path::PathBuf;

use flexrod::beam::MassKind;
use flexrod::modal::ReferenceKind;
use flexrod::rod::{PhysicsSwitch, RodModelKind};
use flexrod::Scene;

/// The rod's shipped scenes, `scenes/*.toml` (not the crankshaft's), sorted.
pub fn shipped_scenes(repository: &std::path::Path) -> Vec<PathBuf> {
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(repository.join("scenes"))
        .expect("read scenes/")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .filter(|p| {
            let text = std::fs::read_to_string(p).unwrap_or_default();
            flexrod::fmi::registry::ModelKind::of_scene_text(&text)
                == flexrod::fmi::registry::ModelKind::Rod
        })
        .collect();
    scenes.sort();
    assert!(scenes.len() >= 7, "{} scenes in scenes/", scenes.len());
    scenes
}

/// The words of `text` that are Rust names rather than the scene's: the `Debug` names of the
/// enumerations a scene sets, and any CamelCase word (a lower-case letter followed by a capital)
/// other than the scene's `name`.
pub fn rust_names(text: &str, scene: &Scene) -> Vec<String> {
    let mut debug: Vec<String> = Vec::new();
    debug.extend(RodModelKind::ALL.iter().map(|k| format!("{k:?}")));
    debug.extend(ReferenceKind::ALL.iter().map(|k| format!("{k:?}")));
    debug.extend(MassKind::ALL.iter().map(|k| format!("{k:?}")));
    debug.extend(PhysicsSwitch::ALL.iter().map(|k| format!("{k:?}")));
    let camel = |w: &str| {
        w.as_bytes()
            .windows(2)
            .any(|p| p[0].is_ascii_lowercase() && p[1].is_ascii_uppercase())
    };
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty() && *w != scene.name)
        .filter(|w| debug.iter().any(|d| d == w) || camel(w))
        .map(String::from)
        .collect()
}
