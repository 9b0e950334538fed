//! Shading work: the edge mask's share of the pixels and the shaded samples per pixel it
//! implies, from a pipeline's "debug.edges" output (red where lighting runs per sample,
//! blue where once per pixel, black without geometry), or from its kind when it has none.
//! A pipeline that shades an edge pixel once per fragment (adaptive shading) exports
//! "debug.fragments" too, and its edge pixels count their fragments instead of samples.

use image::RgbaImage;
use rgraph_core::Plan;
use serde::Serialize;

/// The output every deferred pipeline with an edge pass exports.
pub const EDGES_OUTPUT: &str = "debug.edges";
/// The output of pipelines that shade an edge pixel once per fragment: fragments per
/// pixel, green 2, blue 3, red 4 or more (light_tiled's `fragments` view).
pub const FRAGMENTS_OUTPUT: &str = "debug.fragments";

#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Work {
    /// Pixels marked for per-sample shading, over all pixels; `None` without an edge mask.
    pub edge_pixel_share: Option<f64>,
    /// Shading-shader invocations per pixel: non-edge pixels once, edge pixels once per
    /// sample (background pixels count once: the full-screen light passes run there too).
    pub shaded_samples_per_pixel: Option<f64>,
    /// Where the figure comes from: "debug.edges", or "kind: ..." for pipelines without
    /// an edge mask, or why it is missing.
    pub source: String,
    /// The least shading a pixel needs, one per distinct surface among its samples
    /// (see surfaces.rs), for pipelines at the sample count it was counted at; `null`
    /// otherwise and in sweeps.
    pub unique_surface_bound: Option<f64>,
}

impl Work {
    /// From the edge share of a pipeline whose multisampled targets have `samples`
    /// samples.
    pub fn from_edges(share: f64, samples: u32) -> Work {
        Work {
            edge_pixel_share: Some(share),
            shaded_samples_per_pixel: Some(1.0 + share * (samples as f64 - 1.0)),
            source: EDGES_OUTPUT.into(),
            unique_surface_bound: None,
        }
    }

    /// From an edge mask and a fragments view of the same frame (adaptive shading): edge
    /// pixels shaded once per fragment, the rest once.
    pub fn from_fragments(edges: &RgbaImage, fragments: &RgbaImage) -> Work {
        let pixels = (edges.width() as usize * edges.height() as usize).max(1);
        let shaded: u64 = edges
            .pixels()
            .zip(fragments.pixels())
            .map(|(e, f)| match is_edge(e.0) {
                true => fragment_count(f.0),
                false => 1,
            })
            .sum();
        Work {
            edge_pixel_share: Some(edge_share(edges)),
            shaded_samples_per_pixel: Some(shaded as f64 / pixels as f64),
            source: format!("{EDGES_OUTPUT} and {FRAGMENTS_OUTPUT}"),
            unique_surface_bound: None,
        }
    }

    /// For a pipeline whose edge mask its file's conditions drop for this scene (`why`).
    pub fn not_made(why: &str) -> Work {
        Work {
            edge_pixel_share: None,
            shaded_samples_per_pixel: None,
            source: format!("not counted: {EDGES_OUTPUT} is not made for this scene ({why})"),
            unique_surface_bound: None,
        }
    }

    /// For a pipeline without an edge mask, from its kind (its file name): how often its
    /// shading shader runs per pixel, `supersampling` being its shaded samples per pixel
    /// when every sample is shaded.
    pub fn from_kind(stem: &str, samples: u32, supersampling: u32) -> Work {
        let kind = KINDS.iter().find(|(prefix, _, _)| stem.starts_with(prefix));
        let (rate, source) = match kind {
            Some((_, Rate::One, why)) => (Some(1.0), format!("kind: {why}")),
            Some((_, Rate::Samples, why)) => (Some(samples as f64), format!("kind: {why}")),
            Some((_, Rate::Supersampled, why)) => {
                (Some(supersampling as f64), format!("kind: {why}"))
            }
            None => (
                None,
                "not counted: no debug.edges output and not a known kind".into(),
            ),
        };
        Work {
            edge_pixel_share: None,
            shaded_samples_per_pixel: rate,
            source,
            unique_surface_bound: None,
        }
    }
}

/// A plan's sample count (the most samples of any texture it uses) and its shaded samples
/// per output pixel when every sample is shaded (samples times the area of the largest
/// multisampled target over the output's: 16 for 4x MSAA at twice the size).
pub fn sampling(plan: &Plan) -> (u32, u32) {
    let (width, height) = plan.output_size;
    let output_area = (width as u64 * height as u64).max(1);
    plan.resources
        .iter()
        .filter(|r| r.lifetime.is_some())
        .filter_map(|r| r.texture)
        .fold((1, 1), |(samples, supersampling), t| {
            let area = t.width as u64 * t.height as u64;
            let shaded = (t.samples as u64 * area / output_area) as u32;
            (samples.max(t.samples), supersampling.max(shaded))
        })
}

enum Rate {
    One,
    Samples,
    Supersampled,
}

/// Pipelines without "debug.edges", by file-name prefix: what their shading runs per pixel.
const KINDS: &[(&str, Rate, &str)] = &[
    (
        "forward_msaa",
        Rate::One,
        "forward MSAA shades once per fragment (more where triangles meet inside a pixel)",
    ),
    (
        "deferred_gbuffer_resolve",
        Rate::One,
        "lights the resolved G-buffer once per pixel",
    ),
    (
        "deferred_onthefly_resolve",
        Rate::Samples,
        "shades every sample of every pixel and averages them",
    ),
    (
        "reference_ssaa",
        Rate::Supersampled,
        "shades every sample of the supersampled target",
    ),
];

/// The share of pixels a pipeline's "debug.edges" view marks as edges: red ones (the
/// view writes pure red, blue or black).
pub fn edge_share(view: &RgbaImage) -> f64 {
    let edges = view.pixels().filter(|p| is_edge(p.0)).count();
    edges as f64 / (view.width() as usize * view.height() as usize).max(1) as f64
}

fn is_edge(p: [u8; 4]) -> bool {
    p[0] > 127 && p[2] <= 127
}

/// Fragments of a pixel as [`FRAGMENTS_OUTPUT`] colours it: green 2, blue 3, red 4 (or
/// more), anything else 1.
fn fragment_count(p: [u8; 4]) -> u64 {
    match (p[0] > 127, p[1] > 127, p[2] > 127) {
        (false, true, false) => 2,
        (false, false, true) => 3,
        (true, false, false) => 4,
        _ => 1,
    }
}

#[cfg(test)]
mod tests {
    use image::{Rgba, RgbaImage};

    use super::{edge_share, Work};

    #[test]
    fn adaptive_edge_pixels_cost_a_shading_per_fragment() {
        let red = Rgba([255, 0, 0, 255]);
        let mut edges = RgbaImage::from_pixel(4, 1, Rgba([0, 0, 255, 255]));
        edges.put_pixel(0, 0, red);
        edges.put_pixel(1, 0, red);
        let mut fragments = RgbaImage::from_pixel(4, 1, Rgba([26, 26, 26, 255]));
        fragments.put_pixel(0, 0, Rgba([0, 255, 0, 255]));
        fragments.put_pixel(1, 0, Rgba([0, 0, 255, 255]));
        // Several fragments off the edge mask are shaded once: the pixel is not an edge.
        fragments.put_pixel(2, 0, red);
        let work = Work::from_fragments(&edges, &fragments);
        assert_eq!(work.edge_pixel_share, Some(0.5));
        assert_eq!(
            work.shaded_samples_per_pixel,
            Some((2.0 + 3.0 + 1.0 + 1.0) / 4.0)
        );
    }

    #[test]
    fn red_pixels_are_edges_and_cost_a_shading_per_sample() {
        let mut image = RgbaImage::from_pixel(4, 1, Rgba([0, 0, 255, 255]));
        image.put_pixel(0, 0, Rgba([255, 0, 0, 255]));
        image.put_pixel(1, 0, Rgba([0, 0, 0, 255]));
        let work = Work::from_edges(edge_share(&image), 4);
        assert_eq!(work.edge_pixel_share, Some(0.25));
        assert_eq!(work.shaded_samples_per_pixel, Some(1.75));
    }

    #[test]
    fn pipelines_without_a_mask_count_by_kind() {
        let shaded = |stem| Work::from_kind(stem, 4, 16).shaded_samples_per_pixel;
        assert_eq!(shaded("forward_msaa_4x"), Some(1.0));
        assert_eq!(shaded("deferred_onthefly_resolve_4x"), Some(4.0));
        assert_eq!(shaded("reference_ssaa16"), Some(16.0));
        assert_eq!(shaded("my_pipeline"), None);
    }
}
