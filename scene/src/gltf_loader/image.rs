//! Material images, decoded to RGBA8.

use super::uri_error::UriError;
use super::{accessor, uri, Loader};
use crate::error::label;
use crate::{SceneError, TextureImage};

/// Bytes a decoder may allocate per pixel of the header's size: 16-bit RGBA, the widest
/// PNG, before conversion to RGBA8.
const DECODED_BYTES_PER_PIXEL: u64 = 8;

/// What a decoder may allocate besides the pixels: palettes, ICC profiles, text chunks.
const DECODER_OVERHEAD_BYTES: u64 = 64 << 20;

impl Loader<'_> {
    /// The scene texture index of glTF image `index` as `srgb` color data or linear data,
    /// decoding it (PNG or JPEG, from a buffer view, a data URI or a file) on first use in
    /// that role. `slot` and `material` name the user in errors. Its memory is taken from
    /// the budget before decoding (see `reserve`), and the decoder may allocate no more than
    /// the header's size calls for (see [`Loader::decode`]).
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
        self.reserve_image(index, srgb, slot, material)?;
        let decoded = self.decode(index, slot, material)?;
        self.builder.textures.push(TextureImage {
            name: self.image_name(index),
            width: decoded.width(),
            height: decoded.height(),
            rgba8: decoded.into_raw(),
            srgb,
        });
        let texture = self.builder.textures.len() - 1;
        self.images.insert((index, srgb), texture);
        Ok(texture)
    }

    /// glTF image `index` decoded to RGBA8, the decoder allowed no more than its header's
    /// size calls for. Takes nothing from the budget: the caller has (`reserve`).
    pub(super) fn decode(
        &mut self,
        index: usize,
        slot: &'static str,
        material: &str,
    ) -> Result<::image::RgbaImage, SceneError> {
        let (width, height) = self.image_size(index, slot, material)?;
        let mut limits = ::image::Limits::default();
        limits.max_image_width = Some(width);
        limits.max_image_height = Some(height);
        limits.max_alloc = Some(
            u64::from(width) * u64::from(height) * DECODED_BYTES_PER_PIXEL + DECODER_OVERHEAD_BYTES,
        );
        let mut reader = ::image::ImageReader::new(std::io::Cursor::new(&self.encoded[&index]))
            .with_guessed_format()
            .map_err(|e| self.image_error(index, slot, material, format!("cannot decode: {e}")))?;
        reader.limits(limits);
        Ok(reader
            .decode()
            .map_err(|e| self.image_error(index, slot, material, format!("cannot decode: {e}")))?
            .into_rgba8())
    }

    /// The encoded bytes of glTF image `index` (from a buffer view, a data URI or a file),
    /// read once into `self.encoded`.
    pub(super) fn encoded(&mut self, index: usize) -> Result<&[u8], UriError> {
        if !self.encoded.contains_key(&index) {
            // The JSON is read directly: gltf's `Image::source` unwraps fields a malformed
            // file may lack.
            let json = &self.document.as_json().images[index];
            let bytes = match (&json.buffer_view, &json.uri) {
                (Some(view), _) => {
                    let view = self.document.views().nth(view.value()).ok_or_else(|| {
                        UriError::Invalid(format!("no buffer view {}", view.value()))
                    })?;
                    accessor::view_bytes(&self.buffers, &view)
                        .map_err(UriError::Invalid)?
                        .to_vec()
                }
                (None, Some(uri)) => uri::read(&self.sandbox, uri)?,
                (None, None) => {
                    return Err(UriError::Invalid(
                        "has neither uri nor bufferView".to_owned(),
                    ))
                }
            };
            self.encoded.insert(index, bytes);
        }
        Ok(&self.encoded[&index])
    }

    /// An error about glTF image `index`, used as the material's `slot` texture.
    pub(super) fn image_error(
        &self,
        index: usize,
        slot: &'static str,
        material: &str,
        reason: String,
    ) -> SceneError {
        SceneError::InvalidImage {
            file: self.file.to_owned(),
            image: self.image_name(index),
            slot,
            material: material.to_owned(),
            reason,
        }
    }

    /// glTF image `index` as messages name it: its name, else its file's (a data URI is no
    /// name: it is the whole image).
    pub(super) fn image_name(&self, index: usize) -> String {
        let json = &self.document.as_json().images[index];
        let file_name = json.uri.as_deref().filter(|uri| !uri.starts_with("data:"));
        label("image", index, json.name.as_deref().or(file_name))
    }
}
