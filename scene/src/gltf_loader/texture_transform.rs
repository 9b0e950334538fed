//! KHR_texture_transform: a texture reference's offset, rotation and scale of its UVs.

use serde_json::Value;

/// The extension's fields as glTF writes them (all optional).
#[derive(serde::Deserialize)]
struct TransformJson {
    #[serde(default)]
    offset: Option<[f32; 2]>,
    #[serde(default)]
    rotation: Option<f32>,
    #[serde(default)]
    scale: Option<[f32; 2]>,
    #[serde(default, rename = "texCoord")]
    tex_coord: Option<u32>,
}

/// A texture reference's transform: the matrix [`crate::TextureRef::uv_transform`]
/// holds and the UV set that overrides the reference's own, if the extension names one.
pub(super) struct UvTransform {
    pub matrix: [[f32; 2]; 3],
    pub tex_coord: Option<u32>,
}

/// The transform the extension object `value` describes: `uv' = offset + R(rotation) *
/// (scale * uv)`, rotation counter-clockwise in UV space, which is the image turned
/// clockwise (the extension's example, offset (0, 1), rotation 90° and scale 0.5, shows the
/// image's lower left quadrant). Errors name what is wrong, for a warning.
pub(super) fn read(value: &Value) -> Result<UvTransform, String> {
    let json: TransformJson = serde_json::from_value(value.clone())
        .map_err(|e| format!("KHR_texture_transform cannot be read: {e}"))?;
    let [sx, sy] = json.scale.unwrap_or([1.0, 1.0]);
    let offset = json.offset.unwrap_or([0.0, 0.0]);
    let (sin, cos) = json.rotation.unwrap_or(0.0).sin_cos();
    let matrix = [[cos * sx, -sin * sx], [sin * sy, cos * sy], offset];
    if matrix.iter().flatten().any(|c| !c.is_finite()) {
        return Err("KHR_texture_transform has a value that is not finite".to_owned());
    }
    Ok(UvTransform {
        matrix,
        tex_coord: json.tex_coord,
    })
}
