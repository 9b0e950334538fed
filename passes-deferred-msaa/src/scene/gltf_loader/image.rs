//! Material images, decoded to RGBA8.

use super::{accessor, uri, Loader};
use crate::scene::error::label;
use crate::scene::{SceneError, TextureImage};

impl Loader<'_> {
    /// The scene texture index of glTF image `index` as `srgb` color data or linear data,
    /// decoding it (PNG or JPEG, from a buffer view, a data URI or a file) on first use in
    /// that role. `slot` and `material` name the user in errors.
    pub(super) fn image(
        &mut self,
        index: usize,
        srgb: bool,
        slot: &'static str,
        material: &str,
    ) -> Result<usize, SceneError> {
        if let Some(&texture) = self.images.get(&(index, srgb)) {
            return Ok(texture);
        }
        // The JSON is read directly: gltf's `Image::source` unwraps fields a malformed file
        // may lack.
        let json = &self.document.as_json().images[index];
        // A data URI is no name: it is the whole image.
        let file_name = json.uri.as_deref().filter(|uri| !uri.starts_with("data:"));
        let name = label("image", index, json.name.as_deref().or(file_name));
        let invalid = |reason: String| SceneError::InvalidImage {
            file: self.file.to_owned(),
            image: name.clone(),
            slot,
            material: material.to_owned(),
            reason,
        };
        let encoded = match (&json.buffer_view, &json.uri) {
            (Some(view), _) => {
                let view = self
                    .document
                    .views()
                    .nth(view.value())
                    .ok_or_else(|| invalid(format!("no buffer view {}", view.value())))?;
                accessor::view_bytes(&self.buffers, &view)
                    .map_err(invalid)?
                    .to_vec()
            }
            (None, Some(uri)) => {
                uri::read(&self.sandbox, uri).map_err(|e| e.into_named_error(invalid))?
            }
            (None, None) => return Err(invalid("has neither uri nor bufferView".to_owned())),
        };
        // Reserved from the header's size before decoding: a few kilobytes of PNG can hold
        // hundreds of megabytes of pixels. RGBA8 plus a third for the mip chain.
        let size = ::image::ImageReader::new(std::io::Cursor::new(&encoded))
            .with_guessed_format()
            .ok()
            .and_then(|reader| reader.into_dimensions().ok());
        if let Some((width, height)) = size {
            let bytes = u64::from(width) * u64::from(height) * 4 / 3 * 4;
            let why = format!("decoding it ({width}x{height})");
            self.budget.take(bytes, &why).map_err(invalid)?;
        }
        let decoded = ::image::load_from_memory(&encoded)
            .map_err(|e| invalid(format!("cannot decode: {e}")))?
            .into_rgba8();
        self.builder.textures.push(TextureImage {
            name,
            width: decoded.width(),
            height: decoded.height(),
            rgba8: decoded.into_raw(),
            srgb,
        });
        let texture = self.builder.textures.len() - 1;
        self.images.insert((index, srgb), texture);
        Ok(texture)
    }
}
