//! The finite segment rod (seed 002): rigid segments joined by rotational springs.

use crate::beam::RodProperties;
use crate::error::ModelError;
use crate::mechanism::RodBody;
use crate::scene::Scene;

/// Build the segment rod of a scene.
pub fn build(_scene: &Scene, _props: RodProperties) -> Result<Box<dyn RodBody>, ModelError> {
    Err(ModelError::InvalidParameter {
        name: "rod.model",
        value: 1.0,
        allowed: "ffr (the segments model is not built yet)".into(),
    })
}
