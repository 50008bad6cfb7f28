//! The models this library exports as FMUs, and the one place of the FMI shell that names
//! them: which model a scene describes, and how to build it for a standard's interface. The
//! rest of the shell drives any [`CoSimulationModel`] (checked by `tests/layers.rs`).
//!
//! A scene file describes one model (`docs/fmu.md`, "Models"):
//! - a `[crankshaft]` table: the crankshaft and flywheel ([`CrankshaftModel`]);
//! - otherwise: the slider-crank with its flexible rod ([`RodModel`]).

use super::description::ModelDescription;
use super::standard::Standard;
use crate::cosimulation::CoSimulationModel;
use crate::crankshaft::{CrankshaftModel, CrankshaftScene};
use crate::error::ModelError;
use crate::model::RodModel;
use crate::scene::Scene;

/// The kinds of model a scene file can describe.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelKind {
    /// The slider-crank with its flexible connecting rod.
    Rod,
    /// The crankshaft and flywheel.
    Crankshaft,
}

impl ModelKind {
    /// The kind a scene's text describes: a top-level `crankshaft` table makes it the
    /// crankshaft; text that is not TOML is left to the rod's parser to report.
    pub fn of_scene_text(text: &str) -> ModelKind {
        match text.parse::<toml::Table>() {
            Ok(table) if table.contains_key(CrankshaftScene::TABLE) => ModelKind::Crankshaft,
            _ => ModelKind::Rod,
        }
    }
}

/// The model a scene's text describes, with its variables declared for `standard`.
/// `origin` names the text in messages.
pub fn model_from_scene_text(
    text: &str,
    origin: &str,
    standard: Standard,
) -> Result<Box<dyn CoSimulationModel>, String> {
    match ModelKind::of_scene_text(text) {
        ModelKind::Rod => {
            let scene = Scene::from_toml_str(text, origin).map_err(|e| e.to_string())?;
            rod_model(scene, standard)
                .map_err(|e| format!("the scene {origin} cannot be built: {e}"))
        }
        ModelKind::Crankshaft => {
            let scene = CrankshaftScene::from_toml_str(text, origin)?;
            let model = CrankshaftModel::new(scene, standard.interface())?;
            Ok(Box::new(model))
        }
    }
}

/// The rod's model of `scene` for `standard`.
pub fn rod_model(
    scene: Scene,
    standard: Standard,
) -> Result<Box<dyn CoSimulationModel>, ModelError> {
    Ok(Box::new(RodModel::new(scene, standard.interface())?))
}

/// The compiled-in default scene's model (the benchmark rod), for an FMU whose resources
/// cannot be read.
pub fn default_model(standard: Standard) -> Result<Box<dyn CoSimulationModel>, ModelError> {
    rod_model(Scene::benchmark(), standard)
}

impl ModelDescription {
    /// The FMI 2.0 description of the rod's `scene` (builds the model once to count the
    /// natural frequencies).
    pub fn for_scene(scene: &Scene) -> Result<ModelDescription, ModelError> {
        ModelDescription::for_standard(scene, Standard::Fmi2)
    }

    /// The FMI 3.0 description of the rod's `scene`.
    pub fn for_scene_fmi3(scene: &Scene) -> Result<ModelDescription, ModelError> {
        ModelDescription::for_standard(scene, Standard::Fmi3)
    }

    /// The description of the rod's `scene` in `standard`.
    pub fn for_standard(scene: &Scene, standard: Standard) -> Result<ModelDescription, ModelError> {
        ModelDescription::of(&*rod_model(scene.clone(), standard)?, standard)
    }

    /// The description of the model a scene's text describes, in `standard`.
    pub fn for_scene_text(
        text: &str,
        origin: &str,
        standard: Standard,
    ) -> Result<ModelDescription, String> {
        let model = model_from_scene_text(text, origin, standard)?;
        ModelDescription::of(&*model, standard).map_err(|e| e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::variables::{Interface, VariableTable};

    fn fmi2(scene: &Scene) -> ModelDescription {
        let table = VariableTable::for_interface(scene, 6, Standard::Fmi2.interface());
        let model = RodModel::with_table(scene.clone(), table).unwrap();
        ModelDescription::of(&model, Standard::Fmi2).unwrap()
    }

    #[test]
    fn description_depends_on_start_values() {
        let scene = Scene::benchmark();
        let a = fmi2(&scene);
        let mut other = scene.clone();
        other.rod.length = 0.31;
        let b = fmi2(&other);
        assert_ne!(a.guid, b.guid);
        assert!(a.xml.contains(&a.guid));
        assert!(a.xml.contains("canSerializeFMUstate=\"true\""));
        assert_eq!(a.xml.matches("canRunAsynchronuously").count(), 1);
    }

    #[test]
    fn non_finite_values_are_not_written() {
        let mut scene = Scene::benchmark();
        scene.experiment.stop_time = f64::INFINITY;
        let table = VariableTable::for_interface(&scene, 6, Interface::SCALARS);
        let model = RodModel::with_table(scene, table).unwrap();
        let e = ModelDescription::of(&model, Standard::Fmi2)
            .err()
            .expect("an infinite stop time is rejected");
        assert!(e.to_string().contains("not finite"), "{e}");
    }

    #[test]
    fn parameter_bounds_are_declared() {
        let xml = fmi2(&Scene::benchmark()).xml;
        assert!(
            xml.contains("<Real unit=\"m\" min=\"0.0\" start=\"0.3048\"/>"),
            "{xml}"
        );
        assert!(
            xml.contains("<Integer min=\"2\" max=\"128\" start=\"8\"/>"),
            "{xml}"
        );
    }

    #[test]
    fn the_kind_follows_the_scene_text() {
        assert_eq!(
            ModelKind::of_scene_text("[rod]\nlength = 0.3"),
            ModelKind::Rod
        );
        assert_eq!(ModelKind::of_scene_text("not toml ["), ModelKind::Rod);
        assert_eq!(
            ModelKind::of_scene_text("[crankshaft]\ninertia = 0.2"),
            ModelKind::Crankshaft
        );
    }
}
