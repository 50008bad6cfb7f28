//! Finding the model an FMU was exported for: its scene `resources/scene.toml` (which model
//! it describes: [`super::registry`]) under the FMI 2.0
//! `fmuResourceLocation` (a URI, percent-decoded) or in the FMI 3.0 `resourcePath` (a plain
//! file-system path, taken as it is: `%` is a character of the folder's name), checked against
//! the GUID or `instantiationToken` the importer passes.

use std::path::PathBuf;

use super::description::ModelDescription;
use super::registry;
use super::standard::Standard;
use crate::cosimulation::CoSimulationModel;

/// File name of the scene inside `resources/`.
pub const SCENE_FILE: &str = "scene.toml";

/// The model, its description and where it came from.
pub struct LoadedModel {
    pub model: Box<dyn CoSimulationModel>,
    pub description: ModelDescription,
    /// "resources/scene.toml at <path>" or "the compiled-in default scene".
    pub origin: String,
}

/// Turn a `file:` URI (as FMI 2.0 requires for `fmuResourceLocation`) into a path:
/// `file:///a/b`, `file://localhost/a/b`, `file:/a/b`, percent-decoded (`%20` = space).
/// A plain absolute path is accepted too, as some importers pass one.
pub fn path_from_uri(uri: &str) -> Result<PathBuf, String> {
    let rest = if let Some(rest) = uri.strip_prefix("file://") {
        let rest = rest.strip_prefix("localhost").unwrap_or(rest);
        if !rest.starts_with('/') {
            return Err(format!(
                "resource location \"{uri}\" names a remote host; allowed: file:///absolute/path"
            ));
        }
        rest
    } else if let Some(rest) = uri.strip_prefix("file:") {
        rest
    } else if uri.starts_with('/') {
        uri
    } else {
        return Err(format!(
            "resource location \"{uri}\" is not a file: URI; allowed: file:///absolute/path"
        ));
    };
    percent_decode(rest)
        .map(PathBuf::from)
        .map_err(|e| format!("resource location \"{uri}\": {e}"))
}

fn percent_decode(text: &str) -> Result<String, String> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("bad percent escape at byte {i}"))?;
            out.push(hex);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| "the decoded path is not UTF-8".to_string())
}

/// Load the scene for an instance: `resources/scene.toml` if the location is usable, else
/// the compiled-in default scene, in both cases only if its GUID is `guid`.
pub fn load_model(resource_location: Option<&str>, guid: &str) -> Result<LoadedModel, String> {
    load_model_for(resource_location, guid, Standard::Fmi2)
}

/// [`load_model`] for an FMU of `standard` (the resource folder from [`resource_folder`]);
/// `guid` is the `instantiationToken` for FMI 3.0.
pub fn load_model_for(
    resource_location: Option<&str>,
    guid: &str,
    standard: Standard,
) -> Result<LoadedModel, String> {
    let from_resources = match resource_location {
        None => Err(format!(
            "no resource location was given ({} is NULL)",
            match standard {
                Standard::Fmi2 => "fmuResourceLocation",
                Standard::Fmi3 => "resourcePath",
            }
        )),
        Some(uri) => load_from_resources(uri, standard),
    };
    match from_resources {
        Ok(model) => check_guid(model, guid),
        Err(reason) => {
            let model = registry::default_model(standard)
                .map_err(|e| format!("{reason}; the compiled-in default scene fails: {e}"))?;
            let description = ModelDescription::of(&*model, standard)
                .map_err(|e| format!("{reason}; the compiled-in default scene fails: {e}"))?;
            if description.guid == guid {
                Ok(LoadedModel {
                    model,
                    description,
                    origin: format!("the compiled-in default scene ({reason})"),
                })
            } else {
                Err(format!(
                    "{reason}; the compiled-in default scene has {} {} but the importer expects {guid}",
                    standard.token_name(),
                    description.guid
                ))
            }
        }
    }
}

/// The resource folder an importer names: FMI 2.0's `fmuResourceLocation` is a URI
/// ([`path_from_uri`], percent-decoded); FMI 3.0's `resourcePath` is an absolute file-system
/// path, used as it is (never decoded: a folder named `a%20b` is that folder).
pub fn resource_folder(location: &str, standard: Standard) -> Result<PathBuf, String> {
    match standard {
        Standard::Fmi2 => path_from_uri(location),
        Standard::Fmi3 => {
            let path = PathBuf::from(location);
            if path.is_absolute() {
                Ok(path)
            } else {
                Err(format!(
                    "resourcePath \"{location}\" is not an absolute path; allowed: the absolute path of the resources folder (FMI 3.0 passes a path, not a URI)"
                ))
            }
        }
    }
}

fn load_from_resources(uri: &str, standard: Standard) -> Result<LoadedModel, String> {
    let path = resource_folder(uri, standard)?.join(SCENE_FILE);
    let text = crate::limits::read_text(&path, crate::limits::SCENE_FILE_CAP, "the scene file")?;
    let origin = path.display().to_string();
    let model = registry::model_from_scene_text(&text, &origin, standard)?;
    let description = ModelDescription::of(&*model, standard)
        .map_err(|e| format!("the scene {origin} cannot be built: {e}"))?;
    Ok(LoadedModel {
        model,
        description,
        origin,
    })
}

fn check_guid(model: LoadedModel, guid: &str) -> Result<LoadedModel, String> {
    if model.description.guid == guid {
        Ok(model)
    } else {
        let name = model.description.standard().token_name();
        Err(format!(
            "{name} mismatch: the importer passed {guid}, but {} describes an FMU with {name} {} \
             (modelDescription.xml and resources/ come from different exports)",
            model.origin, model.description.guid
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_uris() {
        assert_eq!(
            path_from_uri("file:///tmp/a%20b/resources").unwrap(),
            PathBuf::from("/tmp/a b/resources")
        );
        assert_eq!(
            path_from_uri("file://localhost/x/y").unwrap(),
            PathBuf::from("/x/y")
        );
        assert_eq!(path_from_uri("file:/x").unwrap(), PathBuf::from("/x"));
        assert_eq!(
            path_from_uri("/plain/path").unwrap(),
            PathBuf::from("/plain/path")
        );
        assert!(path_from_uri("http://example.com/r").is_err());
        assert!(path_from_uri("file://host/x").is_err());
        assert!(path_from_uri("file:///bad%2").is_err());
        assert!(path_from_uri("file:///bad%zz").is_err());
    }

    #[test]
    fn fmi3_resource_paths_are_not_decoded() {
        for folder in ["/tmp/pct 100%/resources/", "/tmp/a%20b/resources/"] {
            assert_eq!(
                resource_folder(folder, Standard::Fmi3).unwrap(),
                PathBuf::from(folder)
            );
        }
        assert_eq!(
            resource_folder("file:///tmp/a%20b/resources", Standard::Fmi2).unwrap(),
            PathBuf::from("/tmp/a b/resources")
        );
        assert!(resource_folder("relative/resources", Standard::Fmi3).is_err());
        assert!(resource_folder("file:///tmp/r", Standard::Fmi3).is_err());
    }
}
