//! The images a person looks at to see where the error lives, one folder per scene:
//! reference.png, edge_pixels.png, and per pipeline PIPELINE.png, PIPELINE_error.png (the
//! FLIP heat map) and PIPELINE_edges.png (its debug.edges view, when it has one); beside
//! them each pipeline's plan as a page, PIPELINE.plan.html.

use std::path::{Path, PathBuf};

use image::RgbaImage;

use super::error::BenchError;
use crate::commands::{own_folder, write_atomically, write_png};

/// The folder of one scene's images inside the output directory.
pub struct SceneImages {
    pub dir: PathBuf,
}

impl SceneImages {
    /// Creates `out/SLUG`, the slug being the scene spec with every character that is not
    /// a letter, digit, '-' or '.' replaced by '_' (`builtin:lights?count=4` →
    /// `builtin_lights_count_4`); a link at that name is refused, not followed.
    pub fn create(out: &Path, scene: &str) -> Result<SceneImages, BenchError> {
        let dir = out.join(slug(scene));
        own_folder(&dir).map_err(|e| BenchError::Write {
            path: dir.clone(),
            reason: e.to_string(),
        })?;
        Ok(SceneImages { dir })
    }

    /// Writes `NAME.png`.
    pub fn write(&self, name: &str, image: &RgbaImage) -> Result<(), BenchError> {
        let path = self.dir.join(format!("{}.png", slug(name)));
        write_png(&path, image).map_err(|e| BenchError::Write {
            path,
            reason: e.to_string(),
        })
    }

    /// Writes the page `file` (a pipeline's plan: plan_page.rs) beside the images.
    pub fn write_page(&self, file: &str, html: &str) -> Result<(), BenchError> {
        let path = self.dir.join(file);
        write_atomically(&path, html.as_bytes()).map_err(|e| BenchError::Write {
            path,
            reason: e.to_string(),
        })
    }
}

pub fn slug(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '.' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::slug;

    #[test]
    fn slugs_are_file_names() {
        assert_eq!(slug("builtin:lights?count=4"), "builtin_lights_count_4");
        assert_eq!(slug("deferred_msaa_4x@4spp"), "deferred_msaa_4x_4spp");
    }
}
