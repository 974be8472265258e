//! Scene parsing and validation. STUB: the scene helper replaces this file.

use super::Scene;
use crate::error::Error;

pub(super) fn scene_from_json(text: &str) -> Result<Scene, Error> {
    let v: serde_json::Value = serde_json::from_str(text).map_err(|e| Error::Json(e.to_string()))?;
    scene_from_value(&v)
}

pub(super) fn scene_from_value(_v: &serde_json::Value) -> Result<Scene, Error> {
    todo!()
}
