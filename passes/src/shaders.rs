//! The passes' WGSL, composed from the fragments in `wgsl/` behind a generated prelude
//! that fixes the G-buffer sample count (so one source serves 1x and MSAA graphs), and
//! validated by naga when a graph file is loaded: shader mistakes fail `cargo build`
//! (build.rs loads every pipeline) rather than the first frame.

use rgraph_core::file::PluginError;
use rgraph_core::shader::Shader;
use rgraph_core::types::Features;

const COMMON: &str = include_str!("wgsl/common.wgsl");
const SCENE: &str = include_str!("wgsl/scene.wgsl");
/// The material model and a material's textures bound per draw (G-buffer, forward).
const MATERIAL: &str = concat!(
    include_str!("wgsl/material.wgsl"),
    include_str!("wgsl/material_bound.wgsl")
);
pub(crate) const GBUFFER_READ: &str = include_str!("wgsl/gbuffer_read.wgsl");
/// The material model with the scene's texture table, a triangle seen through a pixel
/// from the scene's geometry, and the base colour texel a textured alpha MASK tests: what
/// the visibility rasters add to geometry.wgsl.
const MASK_TEXTURE: &str = concat!(
    include_str!("wgsl/material.wgsl"),
    include_str!("wgsl/material_table.wgsl"),
    include_str!("wgsl/plane_hit.wgsl"),
    include_str!("wgsl/mask_texture.wgsl")
);
const GEOMETRY: &str = include_str!("wgsl/geometry.wgsl");
const TRIANGLE_SETUP: &str = include_str!("wgsl/triangle_setup.wgsl");
/// Where a compute rasteriser's visibility buffer keeps each sample's key.
const KEY_LAYOUT: &str = include_str!("wgsl/key_layout.wgsl");
/// A compute rasteriser's keys as its readers take them (group 1, binding 8).
pub(crate) const KEYS: &str = concat!(
    include_str!("wgsl/key_layout.wgsl"),
    include_str!("wgsl/visibility_samples.wgsl")
);
/// Reads a raster pass's visibility buffer as gbuffer_read.wgsl reads a G-buffer (with
/// geometry.wgsl, and the material model with the scene's texture table).
pub(crate) const VISIBILITY_READ_TEXTURES: &str = concat!(
    include_str!("wgsl/geometry.wgsl"),
    include_str!("wgsl/material.wgsl"),
    include_str!("wgsl/material_table.wgsl"),
    include_str!("wgsl/plane_hit.wgsl"),
    include_str!("wgsl/visibility_textures.wgsl"),
    include_str!("wgsl/visibility_read.wgsl")
);
/// Reads a compute rasteriser's visibility buffer (its keys in group 1) the same way.
pub(crate) const VISIBILITY_READ_SAMPLES: &str = concat!(
    include_str!("wgsl/geometry.wgsl"),
    include_str!("wgsl/material.wgsl"),
    include_str!("wgsl/material_table.wgsl"),
    include_str!("wgsl/plane_hit.wgsl"),
    include_str!("wgsl/key_layout.wgsl"),
    include_str!("wgsl/visibility_samples.wgsl"),
    include_str!("wgsl/visibility_read.wgsl")
);
pub(crate) const VIEW_DEPTH_STORED: &str = include_str!("wgsl/view_depth_stored.wgsl");
pub(crate) const VIEW_DEPTH_FROM_DEPTH: &str = include_str!("wgsl/view_depth_from_depth.wgsl");
pub(crate) const EMITTED_HDR: &str = include_str!("wgsl/emitted_hdr.wgsl");
pub(crate) const EMITTED_RGB9E5: &str = include_str!("wgsl/emitted_rgb9e5.wgsl");
pub(crate) const EMITTED_SURFACE: &str = include_str!("wgsl/emitted_surface.wgsl");
/// Where light_tiled.wgsl's edge pixels are lit: in their tile, or listed for a dispatch
/// of their own (a visibility buffer's).
pub(crate) const EDGES_IN_TILES: &str = include_str!("wgsl/edges_in_tiles.wgsl");
pub(crate) const LIGHT_EDGES_LISTED: &str = include_str!("wgsl/light_edges_listed.wgsl");
const BRDF: &str = include_str!("wgsl/brdf.wgsl");
const SURFACE: &str = include_str!("wgsl/surface.wgsl");
const LIGHTING: &str = include_str!("wgsl/lighting.wgsl");
/// The shadow maps' views in group 0.
const SHADOW_VIEWS: &str = include_str!("wgsl/shadow_views.wgsl");
/// lighting.wgsl's `light_visibility` from the shadow atlas (common/shadows.rs binds it).
pub(crate) const SHADOW: &str = concat!(
    include_str!("wgsl/shadow_views.wgsl"),
    include_str!("wgsl/shadow.wgsl")
);
/// lighting.wgsl's `light_visibility` without shadow maps: passes that read no atlas.
pub(crate) const SHADOW_NONE: &str = include_str!("wgsl/shadow_none.wgsl");
const EDGE_DETECT: &str = include_str!("wgsl/edge_detect.wgsl");
/// The shadow maps' debug views' colours, after lighting.wgsl and a shadow block.
const SHADOW_DEBUG: &str = include_str!("wgsl/shadow_debug.wgsl");

/// A pass's shader: a name for messages and its own fragment, composed after the shared
/// fragments it needs.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Source {
    name: &'static str,
    parts: &'static [&'static str],
}

pub(crate) const GBUFFER: Source = Source {
    name: "gbuffer.wgsl",
    parts: &[COMMON, SCENE, MATERIAL, include_str!("wgsl/gbuffer.wgsl")],
};
pub(crate) const EDGE: Source = Source {
    name: "edge.wgsl",
    parts: &[
        COMMON,
        GBUFFER_READ,
        VIEW_DEPTH_STORED,
        EDGE_DETECT,
        include_str!("wgsl/edge.wgsl"),
    ],
};
const LIGHT_WGSL: &str = include_str!("wgsl/light.wgsl");
/// Needs common/ao.rs's and common/shadows.rs's generated blocks after it.
pub(crate) const LIGHT: Source = Source {
    name: "light.wgsl",
    parts: &[
        COMMON,
        SCENE,
        GBUFFER_READ,
        VIEW_DEPTH_STORED,
        BRDF,
        LIGHTING,
        SURFACE,
        include_str!("wgsl/light_shade.wgsl"),
        LIGHT_WGSL,
    ],
};
/// light.wgsl's draws accumulating the light pre-pass's light buffer.
pub(crate) const LIGHT_PREPASS: Source = Source {
    name: "light.wgsl (light pre-pass)",
    parts: &[
        COMMON,
        SCENE,
        GBUFFER_READ,
        VIEW_DEPTH_STORED,
        BRDF,
        LIGHTING,
        SURFACE,
        include_str!("wgsl/light_prepass.wgsl"),
        LIGHT_WGSL,
    ],
};
/// Needs a generated block after it, with a reader ([`GBUFFER_READ`] or
/// [`VISIBILITY_READ`]), one of the `VIEW_DEPTH_*`, one of the `EMITTED_*` fragments and
/// [`EDGES_IN_TILES`] or [`LIGHT_EDGES_LISTED`]: see [`crate::passes::light_tiled::LightTiled`].
pub(crate) const LIGHT_TILED: Source = Source {
    name: "light_tiled.wgsl",
    parts: &[
        COMMON,
        SCENE,
        BRDF,
        LIGHTING,
        SURFACE,
        EDGE_DETECT,
        SHADOW_DEBUG,
        include_str!("wgsl/light_tiled.wgsl"),
    ],
};
/// The shadow maps' depth-only raster (passes/shadow_maps.rs).
pub(crate) const SHADOW_RASTER: Source = Source {
    name: "shadow_raster.wgsl",
    parts: &[
        COMMON,
        SCENE,
        GEOMETRY,
        MASK_TEXTURE,
        SHADOW_VIEWS,
        include_str!("wgsl/shadow_raster.wgsl"),
    ],
};
/// The shadow maps' compute raster (passes/shadow_raster.rs).
pub(crate) const SHADOW_COMPUTE: Source = Source {
    name: "shadow_compute.wgsl",
    parts: &[
        COMMON,
        SCENE,
        GEOMETRY,
        SHADOW_VIEWS,
        include_str!("wgsl/shadow_compute.wgsl"),
    ],
};
/// The shadow atlas from the compute raster's keys (passes/shadow_resolve.rs).
pub(crate) const SHADOW_RESOLVE: Source = Source {
    name: "shadow_resolve.wgsl",
    parts: &[include_str!("wgsl/shadow_resolve.wgsl")],
};
pub(crate) const VISIBILITY: Source = Source {
    name: "visibility.wgsl",
    parts: &[
        COMMON,
        SCENE,
        GEOMETRY,
        MASK_TEXTURE,
        include_str!("wgsl/visibility.wgsl"),
    ],
};
pub(crate) const VISIBILITY_COMPUTE: Source = Source {
    name: "raster_tiles.wgsl",
    parts: &[
        COMMON,
        SCENE,
        GEOMETRY,
        MASK_TEXTURE,
        TRIANGLE_SETUP,
        include_str!("wgsl/tile_raster.wgsl"),
        KEY_LAYOUT,
        include_str!("wgsl/raster_tiles.wgsl"),
    ],
};
/// Micro clusters rasterised a triangle an invocation by 64-bit atomics, before the tile
/// raster (visibility_compute.rs): compose it with [`Source::compose_for`] and
/// [`INT64_ATOMICS`].
pub(crate) const MICRO_RASTER: Source = Source {
    name: "micro_raster.wgsl",
    parts: &[
        COMMON,
        SCENE,
        GEOMETRY,
        MASK_TEXTURE,
        TRIANGLE_SETUP,
        include_str!("wgsl/tile_raster.wgsl"),
        KEY_LAYOUT,
        include_str!("wgsl/micro_raster.wgsl"),
    ],
};
/// The device features a shader with 64-bit atomic max needs (graph-core's device
/// condition `int64_atomics`).
pub(crate) const INT64_ATOMICS: Features =
    Features::SHADER_INT64.union(Features::SHADER_INT64_ATOMIC_MIN_MAX);
pub(crate) const TILE_BINS: Source = Source {
    name: "bin_triangles.wgsl",
    parts: &[
        COMMON,
        SCENE,
        GEOMETRY,
        TRIANGLE_SETUP,
        include_str!("wgsl/bin_triangles.wgsl"),
    ],
};
/// How bin_triangles.wgsl culls clusters by occlusion (visibility_compute.rs): not at
/// all, or in the first or the second of its two phases.
pub(crate) const OCCLUSION_NONE: &str = include_str!("wgsl/occlusion_none.wgsl");
pub(crate) const OCCLUSION_FIRST: &str = concat!(
    include_str!("wgsl/cluster_occlusion.wgsl"),
    include_str!("wgsl/occlusion_first.wgsl")
);
pub(crate) const OCCLUSION_SECOND: &str = concat!(
    include_str!("wgsl/cluster_occlusion.wgsl"),
    include_str!("wgsl/occlusion_second.wgsl")
);
pub(crate) const DEPTH_PYRAMID: Source = Source {
    name: "depth_pyramid.wgsl",
    parts: &[COMMON, SCENE, KEYS, include_str!("wgsl/depth_pyramid.wgsl")],
};
pub(crate) const RESOLVE: Source = Source {
    name: "resolve.wgsl",
    parts: &[COMMON, include_str!("wgsl/resolve.wgsl")],
};
pub(crate) const AUTO_EXPOSURE: Source = Source {
    name: "auto_exposure.wgsl",
    parts: &[COMMON, include_str!("wgsl/auto_exposure.wgsl")],
};
pub(crate) const TONEMAP: Source = Source {
    name: "tonemap.wgsl",
    parts: &[COMMON, SCENE, include_str!("wgsl/tonemap.wgsl")],
};
pub(crate) const FXAA: Source = Source {
    name: "fxaa.wgsl",
    parts: &[COMMON, include_str!("wgsl/fxaa.wgsl")],
};
pub(crate) const SSAO: Source = Source {
    name: "ssao.wgsl",
    parts: &[COMMON, SCENE, include_str!("wgsl/ssao.wgsl")],
};
pub(crate) const DEBUG: Source = Source {
    name: "debug.wgsl",
    parts: &[
        COMMON,
        SCENE,
        GBUFFER_READ,
        VIEW_DEPTH_STORED,
        BRDF,
        include_str!("wgsl/debug.wgsl"),
    ],
};

const FORWARD_WGSL: &str = include_str!("wgsl/forward.wgsl");
/// Needs common/shadows.rs's generated block after it.
pub(crate) const FORWARD: Source = Source {
    name: "forward.wgsl",
    parts: &[COMMON, SCENE, MATERIAL, BRDF, LIGHTING, FORWARD_WGSL],
};
/// forward.wgsl's vertex stages and material model, with the shadow maps' debug views as
/// fragment stages (`forward`'s `view`). Needs common/shadows.rs's generated block too.
pub(crate) const FORWARD_VIEWS: Source = Source {
    name: "forward_views.wgsl",
    parts: &[
        COMMON,
        SCENE,
        MATERIAL,
        BRDF,
        LIGHTING,
        FORWARD_WGSL,
        SHADOW_DEBUG,
        include_str!("wgsl/forward_views.wgsl"),
    ],
};
/// forward.wgsl's vertex stages and shading, with entry points that keep the alpha.
pub(crate) const TRANSPARENT: Source = Source {
    name: "transparent.wgsl",
    parts: &[
        COMMON,
        SCENE,
        MATERIAL,
        BRDF,
        LIGHTING,
        FORWARD_WGSL,
        include_str!("wgsl/transparent.wgsl"),
    ],
};
/// forward.wgsl's vertex stages and material model, with the light pre-pass's thin
/// G-buffer and material entry points.
pub(crate) const LIGHT_PREPASS_GEOMETRY: Source = Source {
    name: "light_prepass_material.wgsl",
    parts: &[
        COMMON,
        SCENE,
        MATERIAL,
        BRDF,
        LIGHTING,
        SHADOW_NONE,
        FORWARD_WGSL,
        include_str!("wgsl/light_prepass_material.wgsl"),
    ],
};
/// Needs a generated block after it: see [`crate::passes::motion_vectors::MotionVectors`].
pub(crate) const MOTION: Source = Source {
    name: "motion.wgsl",
    parts: &[COMMON, SCENE, include_str!("wgsl/motion.wgsl")],
};
/// motion.wgsl's `pixel_motion` from a visibility buffer, whose reader follows it.
pub(crate) const MOTION_OBJECTS: &str = concat!(
    include_str!("wgsl/geometry.wgsl"),
    include_str!("wgsl/material.wgsl"),
    include_str!("wgsl/material_table.wgsl"),
    include_str!("wgsl/plane_hit.wgsl"),
    include_str!("wgsl/motion_objects.wgsl")
);
/// A raster pass's visibility buffer: its IDs (group 1, binding 0) and depth (binding 5).
pub(crate) const VISIBILITY_TEXTURES: &str = include_str!("wgsl/visibility_textures.wgsl");
/// motion.wgsl's `pixel_motion` from a depth buffer, after common/opaque_depth.rs's block,
/// its points standing still.
pub(crate) const MOTION_DEPTH: &str = concat!(
    include_str!("wgsl/motion_depth.wgsl"),
    include_str!("wgsl/motion_still.wgsl")
);
/// motion.wgsl's `pixel_motion` from a depth buffer, after common/opaque_depth.rs's block,
/// its points moved by the meshes a G-buffer's mesh channel names.
pub(crate) const MOTION_DEPTH_MESHES: &str = concat!(
    include_str!("wgsl/motion_depth.wgsl"),
    include_str!("wgsl/motion_meshes.wgsl")
);
pub(crate) const TAA: Source = Source {
    name: "taa.wgsl",
    parts: &[COMMON, include_str!("wgsl/taa.wgsl")],
};
/// Points and lines, unlit, with the camera of scene.wgsl.
pub(crate) const POINTS_LINES: Source = Source {
    name: "points_lines.wgsl",
    parts: &[COMMON, SCENE, include_str!("wgsl/points_lines.wgsl")],
};
pub(crate) const COMPOSITE: Source = Source {
    name: "composite.wgsl",
    parts: &[COMMON, include_str!("wgsl/composite.wgsl")],
};
/// View depth from a depth buffer's value, for the particle passes.
pub(crate) const PARTICLE_DEPTH: &str = include_str!("wgsl/particle_depth.wgsl");
/// Needs a generated block after it: see [`crate::passes::particles::Particles`].
pub(crate) const PARTICLES: Source = Source {
    name: "particles.wgsl",
    parts: &[COMMON, SCENE, include_str!("wgsl/particles.wgsl")],
};
/// particles.wgsl's particles, opacities and blending in compute; needs a generated
/// block after it: see [`crate::passes::particles::Particles`].
pub(crate) const PARTICLES_RASTER: Source = Source {
    name: "particles_raster.wgsl",
    parts: &[
        COMMON,
        SCENE,
        include_str!("wgsl/particles.wgsl"),
        include_str!("wgsl/particles_raster.wgsl"),
    ],
};
pub(crate) const PARTICLE_COMPOSITE: Source = Source {
    name: "particle_composite.wgsl",
    parts: &[COMMON, SCENE, include_str!("wgsl/particle_composite.wgsl")],
};
pub(crate) const DEPTH_DOWNSAMPLE: Source = Source {
    name: "depth_downsample.wgsl",
    parts: &[
        COMMON,
        SCENE,
        PARTICLE_DEPTH,
        include_str!("wgsl/depth_downsample.wgsl"),
    ],
};
/// Needs a generated block after it: see [`crate::passes::background::Background`].
pub(crate) const BACKGROUND: Source = Source {
    name: "background.wgsl",
    parts: &[COMMON, SCENE, include_str!("wgsl/background.wgsl")],
};
pub(crate) const PARTICLE_EDGES: Source = Source {
    name: "particle_edges.wgsl",
    parts: &[COMMON, include_str!("wgsl/particle_edges.wgsl")],
};
pub(crate) const KEYS_DEPTH: Source = Source {
    name: "keys_depth.wgsl",
    parts: &[
        COMMON,
        SCENE,
        KEY_LAYOUT,
        include_str!("wgsl/visibility_samples.wgsl"),
        include_str!("wgsl/keys_depth.wgsl"),
    ],
};
pub(crate) const GBUFFER_RESOLVE: Source = Source {
    name: "gbuffer_resolve.wgsl",
    parts: &[
        COMMON,
        SCENE,
        GBUFFER_READ,
        VIEW_DEPTH_STORED,
        include_str!("wgsl/gbuffer_resolve.wgsl"),
    ],
};

/// tile_raster.wgsl's sample lanes for `samples` per pixel: a pixel's samples as the
/// lanes of one scalar or vector type (groups of four at 8x), so that covering a tile
/// tests them together and keeps its keys in registers, and each sample's position in the
/// pixel as lanes. One sample is a scalar: lanes a pixel does not have are never computed.
/// Nothing for a sample count without known positions (composing the shader names it).
pub(crate) fn sample_lanes(samples: u32) -> String {
    let Some(positions) = sample_positions(samples) else {
        return String::new();
    };
    let lanes = positions.len().min(4);
    let groups = positions.len().div_ceil(4);
    let vector = |scalar: &str| match lanes {
        1 => scalar.to_owned(),
        n => format!("vec{n}<{scalar}>"),
    };
    let axis = |pick: fn(&(f32, f32)) -> f32| {
        let group = |chunk: &[(f32, f32)]| {
            let values: Vec<String> = chunk.iter().map(|p| format!("{:?}", pick(p))).collect();
            format!("LaneF({})", values.join(", "))
        };
        positions
            .chunks(lanes)
            .map(group)
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!(
        "// Generated: a pixel's {samples} sample(s) as {groups} group(s) of {lanes} lane(s).\n\
         alias LaneF = {};\n\
         alias LaneU = {};\n\
         alias LaneB = {};\n\
         const LANES: u32 = {lanes}u;\n\
         const LANE_GROUPS: u32 = {groups}u;\n\
         const LANE_X = array<LaneF, LANE_GROUPS>({});\n\
         const LANE_Y = array<LaneF, LANE_GROUPS>({});\n\
         fn lane(v: LaneU, lane: u32) -> u32 {{\n    return {};\n}}\n",
        vector("f32"),
        vector("u32"),
        vector("bool"),
        axis(|p| p.0),
        axis(|p| p.1),
        if lanes == 1 { "v" } else { "v[lane]" },
    )
}

/// The positions within the pixel of `samples` samples (WebGPU's standard ones), or
/// `None` for a count without them.
pub(crate) fn sample_positions(samples: u32) -> Option<&'static [(f32, f32)]> {
    SAMPLE_POSITIONS
        .iter()
        .find(|(n, _)| *n == samples)
        .map(|(_, positions)| *positions)
}

/// Sample positions within a pixel (y down) by sample count: Vulkan's
/// standardSampleLocations (D3D's), which WebGPU prescribes for its one multisampled
/// count, 4. Per-sample shading reconstructs each sample's surface point there, where
/// the rasterizer tested the sample against the light volumes.
const SAMPLE_POSITIONS: [(u32, &[(f32, f32)]); 4] = [
    (1, &[(0.5, 0.5)]),
    (2, &[(0.75, 0.75), (0.25, 0.25)]),
    (
        4,
        &[
            (0.375, 0.125),
            (0.875, 0.375),
            (0.125, 0.625),
            (0.625, 0.875),
        ],
    ),
    (
        8,
        &[
            (0.5625, 0.3125),
            (0.4375, 0.6875),
            (0.8125, 0.5625),
            (0.3125, 0.1875),
            (0.1875, 0.8125),
            (0.0625, 0.4375),
            (0.6875, 0.9375),
            (0.9375, 0.0625),
        ],
    ),
];

impl Source {
    /// The source for G-buffer textures of `samples` samples, validated.
    pub fn compose(self, samples: u32) -> Result<Shader, PluginError> {
        self.compose_with(samples, "")
    }

    /// [`compose`](Self::compose) with generated WGSL after the fragments: the part of a
    /// shader that varies with the pass's slots.
    pub fn compose_with(self, samples: u32, generated: &str) -> Result<Shader, PluginError> {
        self.compose_for(samples, generated, Features::empty())
    }

    /// As [`Self::compose_with`], for a shader that may use what the optional device
    /// `features` allow (64-bit integers and their atomics): a pass may create it only on
    /// a device that has them.
    pub fn compose_for(
        self,
        samples: u32,
        generated: &str,
        features: Features,
    ) -> Result<Shader, PluginError> {
        let (textures, depth) = if samples > 1 {
            ("texture_multisampled_2d", "texture_depth_multisampled_2d")
        } else {
            ("texture_2d", "texture_depth_2d")
        };
        let Some(positions) = sample_positions(samples) else {
            return Err(PluginError::Invalid(format!(
                "{samples} samples per pixel: the deferred passes know the sample positions \
                 of 1, 2, 4 and 8 samples only"
            )));
        };
        let positions: Vec<String> = positions
            .iter()
            .map(|(x, y)| format!("vec2<f32>({x:?}, {y:?})"))
            .collect();
        let mut text = format!(
            "// Generated: the G-buffer's sample count, texture types and sample positions.\n\
             const SAMPLES: u32 = {samples}u;\n\
             alias GTexF = {textures}<f32>;\n\
             alias GTexU = {textures}<u32>;\n\
             alias GTexD = {depth};\n\
             const SAMPLE_POSITIONS = array<vec2<f32>, {samples}>({});\n\n",
            positions.join(", ")
        );
        for part in self.parts {
            text.push_str(part);
            text.push('\n');
        }
        text.push_str(generated);
        let name = format!("rgraph-passes {} ({samples} sample(s))", self.name);
        Ok(Shader::parse_for(name, text, features)?)
    }
}
