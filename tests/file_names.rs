//! Files under `src/` are named for what they hold. The names below say too little about what a
//! file holds (it has to be read to be known), so none of them is used; each is listed with the
//! file that holds what it would name.

use std::path::{Path, PathBuf};

/// File names not used anywhere under `src/`, each with the file that holds what it would name.
const VAGUE_NAMES: &[(&str, &str)] = &[
    (
        "modal_plain.rs",
        "src/rod/segments/modal_direct_evaluation.rs",
    ),
    (
        "frame_form.rs",
        "src/mechanism/frame_coordinates_closed_form.rs",
    ),
    ("kernel.rs", "src/rod/ffr/fixed_size_integrals.rs"),
    ("loaded.rs", "src/modal/mass_loaded_modes.rs"),
];

/// Paths not used, each with the file that holds what it would name (`body.rs` itself is the
/// name of `src/rod/body.rs`, the `RodBody` trait).
const VAGUE_PATHS: &[(&str, &str)] =
    &[("src/rod/segments/body.rs", "src/rod/segments/dynamics.rs")];

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files(&path, out);
        } else {
            out.push(path);
        }
    }
}

#[test]
fn no_file_under_src_has_a_vague_name() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut found = Vec::new();
    files(&root.join("src"), &mut found);
    let mut vague = Vec::new();
    for path in &found {
        let relative = path
            .strip_prefix(root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let name = path.file_name().unwrap().to_string_lossy();
        for (vague_name, instead) in VAGUE_NAMES {
            if name == *vague_name {
                vague.push(format!("{relative} (see {instead})"));
            }
        }
        for (vague_path, instead) in VAGUE_PATHS {
            if relative == *vague_path {
                vague.push(format!("{relative} (see {instead})"));
            }
        }
    }
    assert!(
        vague.is_empty(),
        "files named too vaguely (name each for what it holds):\n  {}",
        vague.join("\n  ")
    );
    // The replacements exist (the lists name real files).
    for (_, instead) in VAGUE_NAMES.iter().chain(VAGUE_PATHS) {
        assert!(root.join(instead).is_file(), "{instead} does not exist");
    }
}
