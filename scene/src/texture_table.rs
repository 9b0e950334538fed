//! The texture table: how the visibility buffer's shading, one compute pass for every
//! material, reaches every material's textures without binding arrays (which WebGPU does
//! not have, and lavapipe does not support). The scene's images become layers of two 2D
//! array textures, one per encoding (material_table.wgsl reads them):
//!
//! - `color`: rgba8unorm-srgb, the sRGB images (base colour, emissive, specular and sheen
//!   colours);
//! - `data`: rgba8unorm, the linear ones (normal, metallicRoughness, occlusion, specular,
//!   clearcoat, its roughness and normals, sheen roughness).
//!
//! All layers of an array have one size, the largest width and the largest height among
//! its images, and a full mip chain (scene/src/mips.rs). An image of that size is its layer as
//! it is, so it filters exactly as the G-buffer path's texture of its own does; a smaller
//! one is resampled up (bilinear, texel centres aligned) and its mips made from that,
//! which blurs it slightly compared with the G-buffer path. Memory: per array, layers x
//! width x height x 4 bytes x 4/3 (the mips); at least one 1x1 layer where an array has no
//! image.
//!
//! The table is built only where it fits ([`TextureTable::check`]): at most
//! `max_layers` layers per array and `max_side` texels a side (WebGPU's defaults, 256 and
//! 8192, for [`Features`](crate::analysis::Features)' `untabled_textures`; the device's own
//! when uploading), and at most twice the bytes of the scene's own mip-mapped images (what
//! resampling small images up may cost).

use thiserror::Error;

use super::{Scene, TextureImage};

/// WebGPU's default `max_texture_array_layers`: every device has at least this many.
pub const WEBGPU_MAX_LAYERS: u32 = 256;
/// WebGPU's default `max_texture_dimension_2d`.
pub const WEBGPU_MAX_SIDE: u32 = 8192;

/// Where each of a scene's images lies in the table.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureTable {
    /// The sRGB images.
    pub color: TableArray,
    /// The linear images.
    pub data: TableArray,
}

/// One array texture of the table: its layer size and, in layer order, the scene's images.
#[derive(Clone, Debug, PartialEq)]
pub struct TableArray {
    /// Width of every layer, texels.
    pub width: u32,
    /// Height of every layer, texels.
    pub height: u32,
    /// Indices into `Scene::textures`; layer `i` holds `images[i]`.
    pub images: Vec<usize>,
}

/// Why a scene's textures do not fit the table.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum TableError {
    /// More images of one kind than an array texture has layers.
    #[error(
        "the texture table's {array} array would need {layers} layers, more than the \
         {max} a 2D array texture may have (max_texture_array_layers)"
    )]
    TooManyLayers {
        /// Which array: "color" (sRGB) or "data" (linear).
        array: &'static str,
        /// The layers it would need.
        layers: usize,
        /// The limit it exceeds.
        max: u32,
    },
    /// The largest image of one kind is wider or taller than a texture may be.
    #[error(
        "the texture table's {array} layers would be {width}x{height} texels, more than \
         {max} a side (max_texture_dimension_2d)"
    )]
    TooLarge {
        /// Which array: "color" (sRGB) or "data" (linear).
        array: &'static str,
        /// The layers' width, texels.
        width: u32,
        /// The layers' height, texels.
        height: u32,
        /// The limit it exceeds.
        max: u32,
    },
    /// Resampling every image to the largest one's size would more than double the
    /// textures' memory.
    #[error(
        "the texture table would take {table} bytes, more than twice the {own} bytes of \
         the scene's own textures: its images differ so much in size that resampling the \
         small ones up to the largest costs too much"
    )]
    TooMuchMemory {
        /// Bytes the table would take.
        table: u64,
        /// Bytes of the scene's own textures.
        own: u64,
    },
}

impl TableArray {
    fn of<'a>(images: impl Iterator<Item = (usize, &'a TextureImage)>) -> TableArray {
        let mut array = TableArray {
            width: 1,
            height: 1,
            images: Vec::new(),
        };
        for (index, image) in images {
            array.width = array.width.max(image.width);
            array.height = array.height.max(image.height);
            array.images.push(index);
        }
        array
    }

    /// Layers the array texture has: one even without images (a binding needs a texture).
    pub fn layers(&self) -> u32 {
        self.images.len().max(1) as u32
    }

    /// A full chain, down to 1x1.
    pub fn mip_levels(&self) -> u32 {
        32 - self.width.max(self.height).leading_zeros()
    }

    /// Bytes of every layer with its mips.
    pub fn bytes(&self) -> u64 {
        u64::from(self.layers()) * chain_bytes(self.width, self.height)
    }

    /// Every layer's texels, each with its mip chain, layer after layer (wgpu's
    /// `TextureDataOrder::LayerMajor`); `textures` are the scene's images.
    pub fn texels(&self, textures: &[TextureImage]) -> Vec<u8> {
        if self.images.is_empty() {
            // No image: one white layer that nothing samples.
            return vec![255; 4];
        }
        let mut texels = Vec::with_capacity(self.bytes() as usize);
        for &index in &self.images {
            let layer = resampled(&textures[index], self.width, self.height);
            texels.extend_from_slice(&layer.rgba8);
            texels.extend(layer.mip_chain().into_iter().flatten());
        }
        texels
    }
}

impl TextureTable {
    /// The table of `scene`'s images (every image, sampled by a material or not).
    pub fn of(scene: &Scene) -> TextureTable {
        let images = || scene.textures.iter().enumerate();
        TextureTable {
            color: TableArray::of(images().filter(|(_, t)| t.srgb)),
            data: TableArray::of(images().filter(|(_, t)| !t.srgb)),
        }
    }

    /// Image `index`'s array (`true`: `color`) and layer.
    pub fn layer_of(&self, index: usize) -> Option<(bool, u32)> {
        [(true, &self.color), (false, &self.data)]
            .into_iter()
            .find_map(|(color, array)| {
                let layer = array.images.iter().position(|&i| i == index)?;
                Some((color, layer as u32))
            })
    }

    /// Bytes of both arrays.
    pub fn bytes(&self) -> u64 {
        self.color.bytes() + self.data.bytes()
    }

    /// Whether the table of `scene` (`self`) can be built with at most `max_layers` layers
    /// per array and `max_side` texels a side, and takes at most twice the bytes of the
    /// scene's own images with their mips.
    pub fn check(&self, scene: &Scene, max_layers: u32, max_side: u32) -> Result<(), TableError> {
        for (array, a) in [("color", &self.color), ("data", &self.data)] {
            if a.layers() > max_layers {
                return Err(TableError::TooManyLayers {
                    array,
                    layers: a.images.len(),
                    max: max_layers,
                });
            }
            if a.width.max(a.height) > max_side {
                return Err(TableError::TooLarge {
                    array,
                    width: a.width,
                    height: a.height,
                    max: max_side,
                });
            }
        }
        let own: u64 = scene
            .textures
            .iter()
            .map(|t| chain_bytes(t.width, t.height))
            .sum();
        // The placeholder layers of arrays without images are not the images' cost.
        let placeholders = [&self.color, &self.data]
            .iter()
            .filter(|a| a.images.is_empty())
            .count() as u64
            * 4;
        let table = self.bytes() - placeholders;
        if table > 2 * own {
            return Err(TableError::TooMuchMemory { table, own });
        }
        Ok(())
    }
}

/// Bytes of an RGBA8 image of `width` x `height` with its full mip chain.
fn chain_bytes(width: u32, height: u32) -> u64 {
    let (mut w, mut h, mut bytes) = (u64::from(width), u64::from(height), 0);
    loop {
        bytes += w * h * 4;
        if w == 1 && h == 1 {
            return bytes;
        }
        w = (w / 2).max(1);
        h = (h / 2).max(1);
    }
}

/// `image` at `width` x `height`: itself at its own size, else bilinearly resampled with
/// texel centres aligned (edges clamped), in its stored encoding.
pub(crate) fn resampled(image: &TextureImage, width: u32, height: u32) -> TextureImage {
    if (image.width, image.height) == (width, height) {
        return image.clone();
    }
    let texel = |x: i64, y: i64, c: usize| {
        let x = x.clamp(0, i64::from(image.width) - 1) as usize;
        let y = y.clamp(0, i64::from(image.height) - 1) as usize;
        f64::from(image.rgba8[(y * image.width as usize + x) * 4 + c])
    };
    // Where texel centre `i` of `to` lies among the texels of `from`: its lower neighbour
    // and the weight of the upper one.
    let source = |i: u32, from: u32, to: u32| {
        let s = (f64::from(i) + 0.5) * f64::from(from) / f64::from(to) - 0.5;
        (s.floor() as i64, s - s.floor())
    };
    let mut rgba8 = Vec::with_capacity((width * height * 4) as usize);
    for y in 0..height {
        let (y0, fy) = source(y, image.height, height);
        for x in 0..width {
            let (x0, fx) = source(x, image.width, width);
            for c in 0..4 {
                let top = texel(x0, y0, c) * (1.0 - fx) + texel(x0 + 1, y0, c) * fx;
                let bottom = texel(x0, y0 + 1, c) * (1.0 - fx) + texel(x0 + 1, y0 + 1, c) * fx;
                rgba8.push((top * (1.0 - fy) + bottom * fy).round() as u8);
            }
        }
    }
    TextureImage {
        name: image.name.clone(),
        width,
        height,
        rgba8,
        srgb: image.srgb,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(width: u32, height: u32, srgb: bool) -> TextureImage {
        TextureImage {
            name: format!("{width}x{height}"),
            width,
            height,
            rgba8: vec![200; (width * height * 4) as usize],
            srgb,
        }
    }

    fn scene_of(images: Vec<TextureImage>) -> Scene {
        let mut scene = Scene::load("builtin:spheres").expect("a built-in scene");
        scene.textures = images;
        scene
    }

    #[test]
    fn images_of_one_size_cost_what_they_cost_alone() {
        let scene = scene_of(vec![
            image(64, 64, true),
            image(64, 64, false),
            image(64, 64, true),
        ]);
        let table = TextureTable::of(&scene);
        assert_eq!(table.color.images, [0, 2]);
        assert_eq!(table.layer_of(2), Some((true, 1)));
        assert_eq!(table.layer_of(1), Some((false, 0)));
        assert_eq!(table.bytes(), 3 * chain_bytes(64, 64));
        assert_eq!(
            table.check(&scene, WEBGPU_MAX_LAYERS, WEBGPU_MAX_SIDE),
            Ok(())
        );
    }

    #[test]
    fn small_images_are_resampled_up_to_the_largest_within_twice_their_bytes() {
        let scene = scene_of(vec![image(64, 64, true), image(16, 32, true)]);
        let table = TextureTable::of(&scene);
        assert_eq!((table.color.width, table.color.height), (64, 64));
        assert_eq!(
            table.color.texels(&scene.textures).len() as u64,
            table.color.bytes()
        );
        // A uniform image stays uniform.
        assert!(table
            .color
            .texels(&scene.textures)
            .iter()
            .all(|&b| b == 200));
        assert_eq!(
            table.check(&scene, WEBGPU_MAX_LAYERS, WEBGPU_MAX_SIDE),
            Ok(())
        );
        let mut lopsided = vec![image(256, 256, false)];
        lopsided.extend((0..4).map(|_| image(8, 8, false)));
        let lopsided = scene_of(lopsided);
        assert!(matches!(
            TextureTable::of(&lopsided).check(&lopsided, WEBGPU_MAX_LAYERS, WEBGPU_MAX_SIDE),
            Err(TableError::TooMuchMemory { .. })
        ));
    }

    #[test]
    fn more_layers_than_the_device_allows_is_an_error() {
        let scene = scene_of((0..3).map(|_| image(4, 4, false)).collect());
        let error = TextureTable::of(&scene).check(&scene, 2, WEBGPU_MAX_SIDE);
        assert_eq!(
            error,
            Err(TableError::TooManyLayers {
                array: "data",
                layers: 3,
                max: 2
            })
        );
        assert_eq!(
            TextureTable::of(&scene).check(&scene, 256, 2),
            Err(TableError::TooLarge {
                array: "data",
                width: 4,
                height: 4,
                max: 2
            })
        );
    }
}
