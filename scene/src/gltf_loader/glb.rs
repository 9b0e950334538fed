//! The GLB header checked before the `gltf` crate reads it: gltf 1.4 subtracts the header's
//! size from the declared length without checking it, which panics (in builds with
//! overflow checks) on a file that declares less than 12 bytes. Found by tests/fuzz.rs.

use std::path::Path;

use crate::SceneError;

/// The GLB header: magic, version, length.
const HEADER_BYTES: u32 = 12;

/// Fails when `bytes` is a GLB (starts with the magic `glTF`) whose header declares a total
/// length shorter than the header itself.
pub(super) fn check_header(file: &Path, bytes: &[u8]) -> Result<(), SceneError> {
    if !bytes.starts_with(b"glTF") {
        return Ok(());
    }
    let Some(length) = bytes.get(8..12) else {
        return Ok(()); // Too short for a header: `gltf` says so without panicking.
    };
    let length = u32::from_le_bytes(length.try_into().expect("four bytes"));
    if length < HEADER_BYTES {
        return Err(SceneError::InvalidGlb {
            file: file.to_owned(),
            reason: format!(
                "the header declares a length of {length} bytes, less than the header's own \
                 {HEADER_BYTES}"
            ),
        });
    }
    Ok(())
}
