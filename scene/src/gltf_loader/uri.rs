//! Bytes behind glTF URIs and buffers: base64 data URIs, files inside the asset's folder
//! (see [`Sandbox`]), and the GLB binary chunk.

use std::path::Path;

use base64::Engine;

use super::sandbox::Sandbox;
use super::uri_error::UriError;
use crate::SceneError;

/// Reads what `uri` names: a data URI's payload, or a file relative to the glTF file's folder
/// that `sandbox` allows. Errors are either a reason (bad URI, or one leaving the folder) or
/// an I/O error naming the file that could not be read.
pub(super) fn read(sandbox: &Sandbox, uri: &str) -> Result<Vec<u8>, UriError> {
    if let Some(data) = uri.strip_prefix("data:") {
        let (_, payload) = data
            .split_once(";base64,")
            .ok_or_else(|| UriError::Invalid("data URI is not base64".to_owned()))?;
        return base64::engine::general_purpose::STANDARD
            .decode(payload)
            .map_err(|e| UriError::Invalid(format!("bad base64 in data URI: {e}")));
    }
    // A colon before any slash is a scheme (http:, file:, ...): only files next to the asset
    // and data URIs are loaded, so an asset never makes the loader reach out anywhere else.
    if uri
        .split('/')
        .next()
        .is_some_and(|first| first.contains(':'))
    {
        return Err(UriError::Invalid(format!(
            "unsupported URI `{uri}`: only relative paths and data URIs"
        )));
    }
    let relative = urlencoding::decode(uri).map_err(|_| {
        UriError::Invalid(format!("URI `{uri}` is not valid percent-encoded UTF-8"))
    })?;
    sandbox.read(uri, Path::new(&*relative))
}

/// Loads every buffer of the document, in order: the GLB chunk for a buffer without URI, else
/// its URI. Fails when a buffer is shorter than its declared `byteLength`, since accessors are
/// only bounds-checked against what is there.
pub(super) fn load_buffers(
    file: &Path,
    sandbox: &Sandbox,
    document: &gltf::Document,
    mut blob: Option<Vec<u8>>,
) -> Result<Vec<Vec<u8>>, SceneError> {
    document
        .buffers()
        .map(|buffer| {
            let invalid = |reason: String| SceneError::InvalidBuffer {
                file: file.to_owned(),
                buffer: buffer.index(),
                reason,
            };
            let data = match buffer.source() {
                gltf::buffer::Source::Bin => blob.take().ok_or_else(|| {
                    invalid(
                        "refers to the GLB binary chunk, which is missing or already used"
                            .to_owned(),
                    )
                })?,
                gltf::buffer::Source::Uri(uri) => {
                    read(sandbox, uri).map_err(|e| e.into_named_error(invalid))?
                }
            };
            if data.len() < buffer.length() {
                return Err(invalid(format!(
                    "has {} bytes but declares byteLength {}",
                    data.len(),
                    buffer.length()
                )));
            }
            Ok(data)
        })
        .collect()
}
