//! Command-line interface: what each command takes, with help that teaches.

use std::path::PathBuf;

use clap::{Parser, Subcommand, ValueEnum};
use rgraph_core::file::GraphParams;
use rgraph_passes::shadows::{DEFAULT_SHADOWED_LIGHTS, MAX_SHADOWED_LIGHTS};
use rgraph_passes::{Background, Exposure, ShadowFilter, Shadows};
use rgraph_scene::{AssetPolicy, Lighting, Scene, SceneError, DEFAULT_MAX_ASSET_BYTES};

#[derive(Parser)]
#[command(
    name = "rgraph",
    version,
    about = "A render graph on wgpu: RON pipelines checked without a GPU, deferred shading with MSAA",
    long_about = "rgraph compiles render graphs declared in RON files (see pipelines/) into plans: \
                  pass order, culled passes with reasons, texture lifetimes, usages, load/store \
                  operations and pooled memory. Validation and explanation need no GPU; rendering \
                  runs headless on any Vulkan adapter, lavapipe included.",
    after_help = "Examples:\n  rgraph render --out frame.png\n  rgraph bench --out-dir bench/out\n  rgraph validate pipelines/*.ron shaders/*.wgsl\n  rgraph explain --pipeline pipelines/postprocess_demo.ron --format dot | dot -Tpng > plan.png\n  rgraph explain --pipeline pipelines/deferred_msaa_4x.ron --scene builtin:spheres --format html --out plan.html\n  rgraph adapters"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand)]
pub enum Command {
    /// Check graph files (.ron) and shaders (.wgsl) without a GPU.
    ///
    /// Exit status: 0 when every file is valid, 1 when any is not (each problem printed on
    /// stdout as FILE:LINE:COL: error: MESSAGE), 2 for usage or I/O errors (a file that is
    /// not .ron or .wgsl, or cannot be read: named on stderr, the other files still checked).
    Validate {
        /// Graph files (.ron) or WGSL shaders (.wgsl).
        #[arg(required = true, value_name = "FILE")]
        files: Vec<PathBuf>,
        #[command(flatten)]
        target: Target,
        #[command(flatten)]
        roots: GraphRoots,
    },
    /// Print the compiled plan of a graph file: order, lifetimes, usages, load/store,
    /// physical textures and memory, culled passes with the reason. No GPU needed.
    ///
    /// With --scene, the plan is the one for that scene: the scene is analysed, the file
    /// compiled for its features, and (as text) what that drops and saves against the
    /// plan for a scene using every feature is printed after it.
    ///
    /// With --format html, one self-contained page (no network, for a CI artifact): the
    /// passes as a timeline, resource lifetimes coloured by the memory they share, culled
    /// passes with the reason, the scene and parameters; --timings adds a bench's per-pass
    /// times, --compare or --compare-scene marks what differs from another plan.
    ///
    /// Exit status: 0 with the plan on stdout (nothing else goes there) or in --out, 1 when
    /// the file, scene or --timings file is invalid, 2 for usage or I/O errors (as validate;
    /// a --timings file without this pipeline's row); errors go to stderr.
    Explain {
        /// The graph file.
        #[arg(long, value_name = "FILE")]
        pipeline: PathBuf,
        /// Specialise the plan to this scene: a glTF file or builtin:NAME[?params].
        #[arg(long, value_name = "PATH|builtin:NAME")]
        scene: Option<String>,
        /// text for people, dot for Graphviz (culled parts grey), json for tools, html for
        /// a self-contained page (timeline, lifetimes, shared memory, culled passes).
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
        #[command(flatten)]
        target: Target,
        #[command(flatten)]
        samples: Samples,
        #[command(flatten)]
        assets: AssetArgs,
        #[command(flatten)]
        roots: GraphRoots,
        #[command(flatten)]
        page: ExplainArgs,
    },
    /// Render one frame (or a sequence) headless and write it as an 8-bit sRGB PNG.
    ///
    /// Loads the scene, loads the pipeline and keeps only the passes the chosen view needs,
    /// opens the adapter, compiles for it, renders, reads back and writes the PNG
    /// atomically (never a partial file). Progress and a per-pass timing table go to
    /// stderr; stdout gets only the written path. With --frames N, the frames run through
    /// one executor, the camera orbiting by --orbit and the meshes posed by --animation
    /// over --time, one PNG each (one path per line on stdout) and one timing line each on
    /// stderr.
    ///
    /// Exit status: 0 when the PNG was written, 1 when the pipeline, scene or view is
    /// invalid or the frame fails on the device (each problem named), 2 for usage, I/O
    /// and adapter problems.
    #[command(after_long_help = "Examples:\n  \
        rgraph render --out frame.png\n  \
        rgraph render --scene builtin:spheres --width 640 --height 360 --view edges --out edges.png\n  \
        rgraph render --pipeline pipelines/deferred_msaa_4x.ron --scene model.glb \\\n      \
        --tonemap aces --exposure 1.5 --adapter gpu --out model.png\n  \
        rgraph render --frames 36 --orbit 350 --out orbit/%04d.png\n  \
        rgraph render --scene walk.glb --animation walk --time 0..2 --frames 48 \\\n      \
        --out walk/%04d.png")]
    Render(RenderArgs),
    /// Measure every pipeline on every scene: GPU time per pass and frame, memory, edge
    /// work, and image error against a supersampled reference.
    ///
    /// For each scene and pipeline: warmup frames, then measured frames (median and spread
    /// of GPU and CPU times), the plan's memory, the edge mask's share of pixels and the
    /// shading work it implies, and FLIP and PSNR against the reference, on all pixels and
    /// on edge pixels. Writes results.json, results.md, charts and images to --out-dir,
    /// after each scene too (with a note of the scenes still missing), so a run stopped
    /// part way keeps what it measured. A row that cannot be measured (unknown pipeline or scene, a compile or device
    /// failure) is an error row; the rest are still measured.
    ///
    /// Exit status: 0 when at least one row was measured, 1 when none could be, 2 for
    /// usage, I/O and adapter problems.
    #[command(after_long_help = "Examples:\n  \
        rgraph bench --out-dir bench/out\n  \
        rgraph bench --scene builtin:dense --pipeline pipelines/deferred_noaa.ron \\\n      \
        --pipeline pipelines/deferred_msaa_4x.ron --width 640 --height 360 --out-dir out\n  \
        rgraph bench --sweep lights --pipeline pipelines/deferred_msaa_4x.ron --out-dir out/lights")]
    Bench(BenchArgs),
    /// Show a pipeline live in a window, with an orbit camera, a view picker, per-pass GPU
    /// times in the title and hot reload of the graph file and its shaders.
    ///
    /// Needs a display (DISPLAY for X11 or WAYLAND_DISPLAY for Wayland; `xvfb-run` gives a
    /// virtual one). Keys: Left/Right arrows orbit the camera about the scene's bounds
    /// centre (as does dragging with the left mouse button); V or Tab shows the next view
    /// (the pipeline's "color" output, then each "debug.NAME"), with Shift the previous
    /// one; R reloads now; Q or Escape quits. The title shows the view and each pass's GPU
    /// time (the frame time when the device has no timestamps).
    ///
    /// Hot reload: the graph file, the graph files it builds on and the WGSL files they
    /// name are polled every --poll-ms; a change reloads, re-validates and recompiles the
    /// graph, printing `reloaded FILE` on stderr. An invalid edit prints its
    /// FILE:LINE:COL: error: lines on stderr and shows the first in the title, while the
    /// last good graph keeps running.
    ///
    /// Exit status: 0 when the window was closed (or --frames ran), 1 when the first load
    /// of the pipeline, scene or view is invalid, 2 for usage, I/O, adapter or display
    /// problems (no display, a surface the adapter cannot draw into).
    #[command(after_long_help = "Examples:\n  \
        rgraph view\n  \
        rgraph view --pipeline pipelines/deferred_msaa_4x.ron --scene model.glb --view edges\n  \
        xvfb-run -a rgraph view --frames 3 --screenshot shot.png")]
    View(ViewArgs),
    /// List the GPU adapters wgpu can use, with their features and sample counts.
    Adapters {
        /// Also write the profile (limits, features, format capabilities) of the adapter
        /// picked by --adapter to this JSON file, for `--profile FILE` on machines without it.
        #[arg(long, value_name = "FILE")]
        save_profile: Option<PathBuf>,
        /// Adapter for --save-profile: lavapipe, gpu, or part of an adapter's name
        /// (default: $RGRAPH_ADAPTER, else lavapipe).
        #[arg(long)]
        adapter: Option<String>,
    },
    /// Compare two PNG images: the share of pixels
    /// within --tolerance in every channel, the worst difference and where, and mean FLIP.
    /// No GPU needed: for golden-image checks in CI, and for comparing two pipelines'
    /// renders on a GPU server.
    ///
    /// Exit status: 0 when at least --at-least percent of the pixels are within the
    /// tolerance, 1 when fewer are or the sizes differ, 2 when a file cannot be read or a
    /// flag is out of range.
    #[command(after_long_help = "Example:\n  \
        rgraph compare out/visibility.png out/deferred.png --tolerance 1 --at-least 99")]
    Compare {
        /// The two images, of one size.
        #[arg(value_name = "IMAGE")]
        a: PathBuf,
        #[arg(value_name = "IMAGE")]
        b: PathBuf,
        /// The largest difference of one 8-bit channel that still counts as the same.
        #[arg(long, default_value_t = 1, value_name = "N")]
        tolerance: u8,
        /// The share of pixels, in percent, that must be within the tolerance.
        #[arg(long, default_value_t = 100.0, value_name = "PERCENT")]
        at_least: f64,
    },
}

/// What `rgraph render` and `rgraph view` draw: the graph, the scene, the size, the view
/// and the background, on which adapter.
#[derive(clap::Args)]
pub struct FrameArgs {
    /// The graph file. It must export "color" (the final image) and may export debug
    /// views as "debug.NAME"; both rgba8unorm-srgb or rgba8unorm. The default, a
    /// visibility buffer at 4x MSAA, draws every feature a scene has (opaque, alpha MASK
    /// and BLEND, emission, the environment, particles) and is the fastest 4x pipeline.
    /// `view` watches it for changes, with the files it names.
    #[arg(
        long,
        value_name = "FILE",
        default_value = "pipelines/visibility_msaa_4x.ron"
    )]
    pub pipeline: PathBuf,
    /// A glTF 2.0 file (.gltf or .glb), or builtin:NAME[?key=value&...] for a built-in
    /// procedural scene.
    #[arg(
        long,
        value_name = "PATH|builtin:NAME",
        default_value = "builtin:spheres"
    )]
    pub scene: String,
    /// Image width in pixels (for `view` the window's, at whose size the graph renders), at
    /// least 1 and at most the device's largest 2D texture.
    #[arg(long, value_name = "W", default_value_t = 1280, value_parser = parse_dimension)]
    pub width: u32,
    /// Image height in pixels (for `view` the window's), at least 1 and at most the
    /// device's largest 2D texture.
    #[arg(long, value_name = "H", default_value_t = 720, value_parser = parse_dimension)]
    pub height: u32,
    /// What to draw (for `view`, first): final (the pipeline's "color" output) or a debug
    /// view NAME (its "debug.NAME" output): edges, albedo, normals, depth or lights in the
    /// deferred pipelines, and shadows and cascades in deferred_msaa_4x, the tiled ones and
    /// the lean one; edges, fragments, shadows, cascades or motion (each pixel's motion
    /// since the previous frame, grey where still: use it with --frames) in the default
    /// one. Only the passes this view needs run.
    #[arg(long, value_name = "VIEW", default_value = "final")]
    pub view: String,
    /// What shows where nothing is drawn: environment (the scene's, as a mirror reflects
    /// it: the default for files without lights, whose default lighting it is), color:R,G,B
    /// (sRGB bytes 0 to 255 as the PNG shows them, composited in linear light) or
    /// transparent (the PNG's alpha is the coverage, for compositing). Without it a scene
    /// with lights of its own shows black. The pipeline must draw a background (the
    /// default does); others refuse the flag.
    #[arg(long, value_name = "environment|color:R,G,B|transparent", value_parser = parse_background)]
    pub background: Option<Background>,
    #[command(flatten)]
    pub shadows: ShadowArgs,
    /// Adapter to render on: lavapipe, gpu, or part of an adapter's name (default:
    /// $RGRAPH_ADAPTER, else lavapipe). For `view` it must be able to present to the window.
    #[arg(long)]
    pub adapter: Option<String>,
    #[command(flatten)]
    pub samples: Samples,
    #[command(flatten)]
    pub assets: AssetArgs,
    #[command(flatten)]
    pub roots: GraphRoots,
}

impl FrameArgs {
    /// `--width` and `--height`.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }
}

/// How lights cast shadows, for `render`, `view` and `bench`.
#[derive(clap::Args)]
pub struct ShadowArgs {
    /// How lights cast shadows: pcf (percentage-closer filtering, 3 x 3 bilinear
    /// comparison taps), hard (one comparison) or off. Directional (4 cascades), point
    /// (6 cube faces) and spot lights cast them. Off drops the shadow passes.
    #[arg(long = "shadows", value_name = "off|hard|pcf", default_value = "pcf", value_parser = parse_shadow_filter)]
    pub filter: ShadowFilter,
    /// The most lights given shadow maps, 0 to 64: the lights covering most of the
    /// screen, each map sized by its light's share of the screen (from 1024 texels down
    /// to 128 in the 4096-texel atlas), as many as fit.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_SHADOWED_LIGHTS, value_parser = parse_shadowed_lights, allow_negative_numbers = true)]
    pub shadowed_lights: u32,
}

impl ShadowArgs {
    /// `--shadows` and `--shadowed-lights` (each checked by its parser).
    pub fn settings(&self) -> Shadows {
        Shadows {
            filter: self.filter,
            lights: self.shadowed_lights,
        }
    }
}

/// What `rgraph render` draws, how, and where it writes it.
#[derive(clap::Args)]
pub struct RenderArgs {
    #[command(flatten)]
    pub frame: FrameArgs,
    /// Tone mapping in the resolve pass, replacing the pipeline's choice (default: the
    /// pipeline's).
    #[arg(long, value_enum)]
    pub tonemap: Option<Tonemap>,
    /// Exposure before tone mapping, replacing the pipeline's (default: the pipeline's):
    /// a multiplier, above 0 and at most 1e12, or auto: metered from the frame (its average
    /// luminance, between the 10th and 90th percentiles of the lit pixels, mapped to
    /// middle grey), for scenes lit in physical units (a 68,000 lux sun).
    // Negative numbers reach the parser, which explains the rule, instead of clap
    // taking "-1" for an unknown flag.
    #[arg(long, value_name = "E|auto", value_parser = parse_exposure, allow_negative_numbers = true)]
    pub exposure: Option<Exposure>,
    /// Compile the pipeline as for a scene using every feature, instead of dropping the
    /// passes and channels this scene does not use (`rgraph explain --scene` shows what
    /// those are). The image is the same; the point is comparing, or a debug view the
    /// scene's plan drops.
    #[arg(long)]
    pub no_specialise: bool,
    /// The PNG to write (its directory must exist); replaced atomically. With --frames
    /// above 1 the name holds %04d (or %0Nd for N digits), replaced by each frame's number.
    #[arg(long, value_name = "FILE.png", value_parser = parse_file_path)]
    pub out: PathBuf,
    /// Frames to render through one executor, as an engine would: the scene is uploaded
    /// and the pipelines built once, and each later frame only moves the camera.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: u32,
    /// Degrees the camera turns about the vertical axis through the scene's bounds centre
    /// over the frames: frame 0 is the file's (or the default) camera, the last frame is
    /// turned by DEGREES, the frames between evenly spaced. For a seamless loop of N
    /// frames give 360 * (N - 1) / N.
    #[arg(long, value_name = "DEGREES", default_value_t = 0.0, value_parser = parse_degrees, allow_negative_numbers = true)]
    pub orbit: f64,
    /// Pose the scene by its animation NAME (or the one at INDEX, from 0) at --time: its
    /// meshes are drawn where the animation puts them. An unknown one is an error listing
    /// the scene's animations.
    #[arg(long, value_name = "NAME|INDEX")]
    pub animation: Option<String>,
    /// With --animation, seconds: the one frame's time (T; default the animation's start),
    /// or with --frames N above 1 the span the frames cover evenly (T0..T1, frame 0 at T0,
    /// the last at T1; default the animation's first to last key time).
    #[arg(long, value_name = "T|T0..T1", requires = "animation", value_parser = parse_time, allow_negative_numbers = true)]
    pub time: Option<Time>,
}

/// `--time`: one time, or a span of them, in seconds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Time {
    /// One frame's time.
    At(f64),
    /// The first and last frames' times, in order.
    Span(f64, f64),
}

/// What `rgraph view` shows, and how long.
#[derive(clap::Args)]
pub struct ViewArgs {
    #[command(flatten)]
    pub frame: FrameArgs,
    /// Degrees the camera starts turned by about the vertical axis through the scene's
    /// bounds centre, as the last frame of `render --frames N --orbit DEGREES` is.
    #[arg(long, value_name = "DEGREES", default_value_t = 0.0, value_parser = parse_degrees, allow_negative_numbers = true)]
    pub orbit: f64,
    /// Present this many frames, then exit (default: until the window is closed).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: Option<u32>,
    /// With --frames, write the last frame's presented image (read back from the window's
    /// surface) as a PNG when the viewer exits; its directory must exist.
    #[arg(long, value_name = "FILE.png", requires = "frames", value_parser = parse_file_path)]
    pub screenshot: Option<PathBuf>,
    /// How often the watched files' modification times are polled, in milliseconds.
    #[arg(long, value_name = "MS", default_value_t = 200, value_parser = clap::value_parser!(u64).range(1..))]
    pub poll_ms: u64,
}

impl Command {
    /// The folders `--graph-root` names, for the commands that load graph files.
    pub fn graph_roots(&self) -> &[PathBuf] {
        match self {
            Command::Validate { roots, .. } | Command::Explain { roots, .. } => &roots.dirs,
            Command::Render(RenderArgs { frame, .. }) | Command::View(ViewArgs { frame, .. }) => {
                &frame.roots.dirs
            }
            Command::Bench(args) => &args.roots.dirs,
            Command::Adapters { .. } | Command::Compare { .. } => &[],
        }
    }
}

/// `--graph-root DIR`: where graph files' references may also lead.
#[derive(clap::Args)]
pub struct GraphRoots {
    /// A folder a graph file's references (a preset's base, a pass's shader) may also
    /// point into; repeatable. Without it they must stay inside the graph file's own folder
    /// and the shipped pipelines/ and shaders/: an absolute path, a `..` that climbs out or
    /// a symbolic link that leads out is an error naming the reference.
    #[arg(long = "graph-root", value_name = "DIR", value_parser = parse_folder)]
    pub dirs: Vec<PathBuf>,
}

/// The graph-file parameter that is the MSAA sample count:
/// `samples: Param(name: "msaa", default: 4)`.
pub const MSAA: &str = "msaa";

/// `--samples N` and `--param NAME=VALUE`, for one graph file.
#[derive(clap::Args)]
pub struct Samples {
    /// MSAA samples per pixel: the value of the graph file's "msaa" parameter
    /// (`samples: Param(name: "msaa", default: 4)`); a file without one is an error
    /// (default: the file's).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub samples: Option<u32>,
    /// A value for a parameter of the graph file, repeatable: `--param scale=4` for
    /// `size: Divided(Param(name: "scale", default: 2))` or a plugin parameter written
    /// `Param(name: .., default: ..)`. A name the file does not declare is an error.
    #[arg(long = "param", value_name = "NAME=VALUE", value_parser = parse_param)]
    pub param: Vec<(String, u32)>,
}

impl Samples {
    /// The values for the file's parameters these flags ask for.
    pub fn params(&self) -> GraphParams {
        let samples = match self.samples {
            Some(n) => GraphParams::new().with(MSAA, n),
            None => GraphParams::new(),
        };
        self.param
            .iter()
            .fold(samples, |params, (name, value)| params.with(name, *value))
    }
}

/// `NAME=VALUE`, VALUE a whole number that fits the parameter (32 bits).
/// `--motion orbit:DEG`: the degrees, finite.
fn parse_motion(text: &str) -> Result<f64, String> {
    let degrees = text
        .strip_prefix("orbit:")
        .ok_or_else(|| format!("`{text}` is not orbit:DEG (the only motion so far)"))?;
    match degrees.parse::<f64>() {
        Ok(d) if d.is_finite() => Ok(d),
        _ => Err(format!(
            "`{degrees}` in `{text}` is not a finite number of degrees"
        )),
    }
}

fn parse_param(text: &str) -> Result<(String, u32), String> {
    let (name, value) = text
        .split_once('=')
        .ok_or_else(|| format!("`{text}` is not NAME=VALUE"))?;
    Ok((name.to_owned(), parse_param_value(name, value)?))
}

/// `NAME=VALUE[,VALUE..]`: a parameter and the values a bench measures it at.
fn parse_param_values(text: &str) -> Result<(String, Vec<u32>), String> {
    let (name, values) = text
        .split_once('=')
        .ok_or_else(|| format!("`{text}` is not NAME=VALUE or NAME=VALUE,VALUE,.."))?;
    let values = (values.split(','))
        .map(|value| parse_param_value(name, value))
        .collect::<Result<Vec<u32>, String>>()?;
    Ok((name.to_owned(), values))
}

fn parse_param_value(name: &str, value: &str) -> Result<u32, String> {
    value
        .parse()
        .map_err(|e: std::num::ParseIntError| match e.kind() {
            std::num::IntErrorKind::PosOverflow => {
                format!(
                    "`{value}` (parameter {name}) is too large (at most {})",
                    u32::MAX
                )
            }
            _ => format!("`{value}` (parameter {name}) is not a whole number"),
        })
}

/// A file to write (`--out`, `--screenshot`). Text ending in a path separator names a
/// folder, which the checks of the path cannot see (`x.png/` has the file name `x.png`)
/// and which would fail only when the rendered frame is written.
fn parse_file_path(text: &str) -> Result<PathBuf, String> {
    if text.ends_with(std::path::is_separator) {
        return Err(format!(
            "{text} ends with a path separator, so it names a folder, not a file"
        ));
    }
    Ok(PathBuf::from(text))
}

/// A folder that exists (`--asset-root`, `--graph-root`): clap names the flag.
fn parse_folder(text: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(text);
    match std::fs::metadata(&path) {
        Ok(meta) if meta.is_dir() => Ok(path),
        Ok(_) => Err(format!("{text} is a file, not a folder")),
        Err(e) => Err(format!("{text} is not a folder that exists ({e})")),
    }
}

/// What a glTF scene may read besides itself, and which lights it is drawn with.
#[derive(clap::Args)]
pub struct AssetArgs {
    /// The lights to draw with: auto (a file's own, or for a file without lights the
    /// defaults: a neutral studio environment and a headlight, with a warning), file (only
    /// the scene's, even none), default (only the defaults) or both.
    #[arg(long, value_name = "auto|file|default|both", default_value = "auto",
          value_parser = parse_lighting)]
    pub lights: Lighting,
    /// A folder the glTF file's buffer and image URIs may also point into. Without it, a
    /// URI that is an absolute path or climbs out of the glTF file's folder is an error.
    #[arg(long, value_name = "DIR", value_parser = parse_folder)]
    pub asset_root: Option<PathBuf>,
    /// The largest file a scene reads (the glTF file, each buffer, each image), in bytes.
    #[arg(long, value_name = "BYTES", default_value_t = DEFAULT_MAX_ASSET_BYTES,
          value_parser = clap::value_parser!(u64).range(1..))]
    pub max_asset_bytes: u64,
}

impl AssetArgs {
    /// Loads `spec` as these flags say: within the asset policy, lit as `--lights` says.
    pub fn load(&self, spec: &str) -> Result<Scene, SceneError> {
        Ok(Scene::load_with(spec, &self.policy())?.lit(self.lights))
    }

    /// The loader's warnings about `scene`, loaded from `spec`, each after the file's name
    /// as a compiler's are (`FILE: warning: ...`), for the commands to print.
    pub fn warnings<'a>(spec: &'a str, scene: &'a Scene) -> impl Iterator<Item = String> + 'a {
        (scene.warnings.iter()).map(move |warning| format!("{spec}: warning: {warning}"))
    }

    /// The loader's policy these flags ask for.
    pub fn policy(&self) -> AssetPolicy {
        AssetPolicy {
            root: self.asset_root.clone(),
            max_bytes: self.max_asset_bytes,
            ..AssetPolicy::default()
        }
    }
}

/// What `rgraph bench` measures and where it writes the results.
#[derive(clap::Args)]
pub struct BenchArgs {
    /// A scene to measure on (repeat for several): a glTF file or builtin:NAME[?params]
    /// (default: every built-in scene).
    #[arg(long = "scene", value_name = "PATH|builtin:NAME")]
    pub scenes: Vec<String>,
    /// A pipeline to measure (repeat for several; default: every file in pipelines/ that
    /// exports "color").
    #[arg(long = "pipeline", value_name = "FILE")]
    pub pipelines: Vec<PathBuf>,
    /// Image width in pixels.
    #[arg(long, value_name = "W", default_value_t = 1280, value_parser = parse_dimension)]
    pub width: u32,
    /// Image height in pixels.
    #[arg(long, value_name = "H", default_value_t = 720, value_parser = parse_dimension)]
    pub height: u32,
    /// Measured frames of each pipeline per round: a scene's pipelines take turns, N
    /// frames each, in every one of --rounds rounds, and a time is the median of the
    /// rounds' medians.
    #[arg(long, value_name = "N", default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub frames: u32,
    /// Interleaved rounds per scene; a row whose round medians spread (p10 to p90) by
    /// more than 5% of its time is flagged.
    #[arg(long, value_name = "R", default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=100))]
    pub rounds: u32,
    /// Frames of each pipeline run and discarded before round 1 (the first uploads the
    /// scene and creates pipelines), then turns until half a second has passed, unless 0,
    /// so that a GPU that clocked down while the bench measured image error is at speed
    /// again.
    #[arg(long, value_name = "M", default_value_t = 2)]
    pub warmup: u32,
    /// The most pooled memory, in MiB, the plans measured together in one round may ask
    /// for; more pipelines are measured in consecutive groups (default: 60% of the GPU's
    /// memory where nvidia-smi reports it, else 4096).
    #[arg(long, value_name = "MIB", value_parser = clap::value_parser!(u64).range(1..=(1 << 24)))]
    pub group_memory: Option<u64>,
    /// The supersampled reference errors are measured against.
    #[arg(
        long,
        value_name = "FILE",
        default_value = "pipelines/reference_ssaa16.ron"
    )]
    pub reference: PathBuf,
    /// Shading samples per pixel of the reference: 16 runs --reference as written (4x MSAA
    /// at twice the size, every sample shaded), 4 the same at the output size.
    #[arg(long, value_name = "SPP", default_value_t = 16, value_parser = parse_spp)]
    pub reference_spp: u32,
    /// Skip the reference: no image error, for quick time and work tables.
    #[arg(long)]
    pub no_reference: bool,
    /// Measure how cost grows instead, over decades: triangles 10^4..10^8
    /// (builtin:terrain), meshes 1..10^5 (builtin:city), lights 1..65,536
    /// (builtin:lights), resolution 720p..2160p, or samples 1, 2, 4, 8. A value the device
    /// or the scene limits refuse becomes an error row.
    #[arg(long, value_enum)]
    pub sweep: Option<Sweep>,
    /// Measure error over time instead (orbit:DEG): on each --scene (default
    /// builtin:spheres), each --pipeline (default: no AA, FXAA, MSAA 4x, TAA and MSAA 4x +
    /// TAA on the default path) and the reference draw 16 still frames, then
    /// --motion-frames frames with the camera orbiting DEG degrees in all and the scene's
    /// first mesh smaller than a quarter of it (not the ground) moving sideways; motion.md
    /// and motion.json give the still and sequence FLIP, the instability (change beyond the
    /// reference's) and the GPU time of the last frame, timed in rounds as without --motion
    /// (--frames, --rounds, --warmup), per pipeline.
    #[arg(long, value_name = "orbit:DEG", value_parser = parse_motion, conflicts_with = "sweep")]
    pub motion: Option<f64>,
    /// Moving frames of --motion.
    #[arg(long, value_name = "N", default_value_t = 16, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub motion_frames: u32,
    /// The largest sweep value to measure (e.g. --sweep triangles --sweep-max 1000000 on
    /// a CPU adapter, where 10^8 triangles would take hours).
    #[arg(long, value_name = "N", requires = "sweep", value_parser = clap::value_parser!(u32).range(1..))]
    pub sweep_max: Option<u32>,
    /// MSAA samples per pixel for every pipeline whose file has the "msaa" parameter
    /// (`samples: Param(name: "msaa", default: 4)`); the others run as written, and the
    /// results' notes name them (default: each file's; --sweep samples overrides it).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub samples: Option<u32>,
    /// A value for a graph-file parameter, repeatable (`--param scale=4`), given to every
    /// pipeline whose file declares it, whose rows' names then say so ("particles_low_res
    /// [scale=4]"); the results' notes name the files without it. Several values
    /// (`--param shadow_map=1024,2048,4096`) measure such a pipeline once with each, side
    /// by side in the same rounds: a table of the trade the parameter makes.
    #[arg(long = "param", value_name = "NAME=VALUE[,VALUE..]", value_parser = parse_param_values)]
    pub params: Vec<(String, Vec<u32>)>,
    /// Adapter to measure on: lavapipe, gpu, or part of an adapter's name (default:
    /// $RGRAPH_ADAPTER, else lavapipe).
    #[arg(long)]
    pub adapter: Option<String>,
    /// Where results.json, results.md, the charts and the images go (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out_dir: PathBuf,
    #[command(flatten)]
    pub shadows: ShadowArgs,
    #[command(flatten)]
    pub assets: AssetArgs,
    #[command(flatten)]
    pub roots: GraphRoots,
}

/// What `rgraph bench --sweep` varies.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Sweep {
    /// builtin:terrain?cells=N for 10^4, 10^5, 10^6, 10^7 and 10^8 triangles (one mesh).
    Triangles,
    /// builtin:city?blocks=K for 1, 10, 100, 1,000, 10,000 and 100,000 buildings, each
    /// its own mesh.
    Meshes,
    /// builtin:lights?count=N for N = 1, 4, 16, ..., 65,536.
    Lights,
    /// 1280x720, 1920x1080, 2560x1440, 3840x2160.
    Resolution,
    /// Each pipeline's multisampled targets at 1, 2, 4 and 8 samples.
    Samples,
}

/// Tone-mapping operators of the resolve pass.
#[derive(Copy, Clone, PartialEq, Eq, ValueEnum)]
pub enum Tonemap {
    /// Clamp to [0, 1].
    None,
    /// x / (1 + x).
    Reinhard,
    /// The ACES filmic curve.
    Aces,
}

impl Tonemap {
    /// The name the resolve plugin reads from its overrides.
    pub fn name(self) -> &'static str {
        match self {
            Tonemap::None => "none",
            Tonemap::Reinhard => "reinhard",
            Tonemap::Aces => "aces",
        }
    }
}

/// What the graph is compiled for.
#[derive(clap::Args)]
pub struct Target {
    /// Device limits and formats to validate against: `webgpu` (the defaults every device
    /// has), `adapter` (the adapter picked by --adapter / RGRAPH_ADAPTER), or a profile
    /// file (.json) written by `rgraph adapters --save-profile`.
    #[arg(long, default_value = "webgpu", value_name = "webgpu|adapter|FILE")]
    pub profile: String,
    /// The output size relative texture sizes resolve against.
    #[arg(long, default_value = "1920x1080", value_parser = parse_size, value_name = "WxH")]
    pub size: (u32, u32),
    /// Adapter for `--profile adapter`: lavapipe, gpu, or part of an adapter's name
    /// (default: $RGRAPH_ADAPTER, else lavapipe).
    #[arg(long)]
    pub adapter: Option<String>,
}

#[derive(Copy, Clone, PartialEq, Eq, ValueEnum)]
pub enum Format {
    Text,
    Dot,
    Json,
    Html,
}

/// Which outputs `explain` plans for, where it writes, and what its page (`--format
/// html`) adds to the plan.
#[derive(clap::Args)]
pub struct ExplainArgs {
    /// Plan for this output only (repeatable; default: every output the file exports), as
    /// `render --view` and `bench` ("color") do: passes only the other outputs need are
    /// culled, and resources that then live shorter may share memory.
    #[arg(long = "output", value_name = "NAME")]
    pub outputs: Vec<String>,
    /// Write to FILE (replaced atomically) instead of stdout.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// html: each pass's GPU and CPU time from a results.json of `rgraph bench`, the row of
    /// this pipeline (on --scene, when the file has several scenes).
    #[arg(long, value_name = "results.json")]
    pub timings: Option<PathBuf>,
    /// html: mark what differs from the plan of this graph file (compiled for the same
    /// scene and parameters), as a review of a change to the file needs.
    #[arg(long, value_name = "OTHER.ron")]
    pub compare: Option<PathBuf>,
    /// html: mark what differs from the plan for this scene (of --compare's file, if given).
    #[arg(long, value_name = "PATH|builtin:NAME")]
    pub compare_scene: Option<String>,
    /// With --scene: the plan `render --shadows` would run; off drops the shadow passes
    /// (hard and pcf plan alike).
    #[arg(long, value_name = "off|hard|pcf", default_value = "pcf", value_parser = parse_shadow_filter)]
    pub shadows: ShadowFilter,
}

/// A width or height: a whole number of at least 1 (the device's maximum is checked once
/// the device is open).
fn parse_dimension(text: &str) -> Result<u32, String> {
    match text.trim().parse::<u32>() {
        Ok(0) => Err("must be at least 1".into()),
        Ok(v) => Ok(v),
        Err(_) => Err("expected a whole number of pixels".into()),
    }
}

/// Shading samples per pixel of the reference: the two the reference file can make.
fn parse_spp(text: &str) -> Result<u32, String> {
    match text.trim() {
        "16" => Ok(16),
        "4" => Ok(4),
        _ => Err("expected 16 (the reference file as written) or 4 (at the output size)".into()),
    }
}

/// `auto`, or an exposure multiplier: finite and above 0.
fn parse_lighting(text: &str) -> Result<Lighting, String> {
    Lighting::named(text).ok_or_else(|| {
        let names: Vec<&str> = Lighting::ALL.iter().map(|l| l.name()).collect();
        format!("expected one of {}", names.join(", "))
    })
}

fn parse_exposure(text: &str) -> Result<Exposure, String> {
    if text.trim() == "auto" {
        return Ok(Exposure::Auto);
    }
    match text.trim().parse::<f32>() {
        Ok(e) if e.is_finite() && e > Exposure::MAX => Err(format!(
            "{e:e} is too large (at most {:e}): tone mapping squares the exposed color, which \
             would overflow to a black frame",
            Exposure::MAX
        )),
        Ok(e) if e.is_finite() && e > 0.0 => Ok(Exposure::Fixed(e)),
        Ok(_) => Err("must be auto or a finite number above 0".into()),
        Err(_) => Err("expected auto or a number, e.g. 1.5".into()),
    }
}

fn parse_background(text: &str) -> Result<Background, String> {
    let text = text.trim();
    match text {
        "environment" => return Ok(Background::Environment),
        "transparent" => return Ok(Background::Transparent),
        _ => {}
    }
    let expected = "expected environment, transparent or color:R,G,B (each 0 to 255, the \
                    sRGB bytes shown), e.g. color:255,255,255";
    let Some(rgb) = text.strip_prefix("color:") else {
        return Err(format!("{expected}, got \"{text}\""));
    };
    let channels: Vec<&str> = rgb.split(',').collect();
    let parsed: Result<Vec<u8>, _> = channels.iter().map(|c| c.trim().parse::<u8>()).collect();
    match parsed {
        Ok(c) if c.len() == 3 => Ok(Background::Color([c[0], c[1], c[2]])),
        _ => Err(format!("{expected}, got \"{text}\"")),
    }
}

fn parse_time(text: &str) -> Result<Time, String> {
    let seconds = |part: &str| match part.trim().parse::<f64>() {
        Ok(t) if t.is_finite() => Ok(t),
        _ => Err(format!(
            "expected seconds T or a span T0..T1, e.g. 1.5 or 0..2, got \"{text}\""
        )),
    };
    match text.split_once("..") {
        None => Ok(Time::At(seconds(text)?)),
        Some((start, end)) => match (seconds(start)?, seconds(end)?) {
            (start, end) if end < start => Err(format!(
                "the span {text} ends ({end} s) before it starts ({start} s)"
            )),
            (start, end) => Ok(Time::Span(start, end)),
        },
    }
}

fn parse_shadow_filter(text: &str) -> Result<ShadowFilter, String> {
    let text = text.trim();
    (ShadowFilter::ALL.into_iter())
        .find(|filter| filter.name() == text)
        .ok_or_else(|| format!("expected off, hard or pcf, got \"{text}\""))
}

fn parse_shadowed_lights(text: &str) -> Result<u32, String> {
    let lights = text.trim().parse::<u32>().map_err(|_| {
        format!("expected a whole number of lights from 0 to {MAX_SHADOWED_LIGHTS}, got \"{text}\"")
    })?;
    Shadows::new(ShadowFilter::Pcf, lights)
        .map(|s| s.lights)
        .map_err(|e| e.to_string())
}

fn parse_degrees(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(d) if d.is_finite() => Ok(d),
        _ => Err(format!(
            "expected a finite number of degrees, e.g. 90, got \"{text}\""
        )),
    }
}

/// Parses `WIDTHxHEIGHT` with both at least 1.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WIDTHxHEIGHT, e.g. 1280x720, got \"{text}\""))?;
    let parse = |s: &str, what: &str| {
        s.trim()
            .parse::<u32>()
            .map_err(|_| format!("{what} \"{s}\" is not a whole number"))
            .and_then(|v| {
                if v == 0 {
                    Err(format!("{what} must be at least 1"))
                } else {
                    Ok(v)
                }
            })
    };
    Ok((parse(w, "width")?, parse(h, "height")?))
}
