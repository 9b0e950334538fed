//! Long runs hold their memory. Every shipped pipeline and the engine example run 80
//! frames after 20 of settling, `rgraph render --frames` 1,000, the camera orbiting or the
//! example's inputs moving: after the first frame the device objects alive and the
//! device memory they hold never change, resident memory grows by less than 2 MiB, and in
//! this test binary's own runs the live heap by less than 64 KiB. Issue 44's leak
//! (lavapipe compiled the light shaders again at every bind and kept each copy: 1.2 MB a
//! frame in the tiled light pass, 2.6 MB in the fragment light passes) fails it by tens
//! of MiB.
//!
//! Each run is a process of its own, so its memory is its own and no other test moves
//! it: `rgraph render`, or this test binary run again (`soak::child`) for the engine
//! example and for the shipped pipelines, which run one after the other in two such
//! processes, each measured over its own frames (a pipeline's device objects are gone
//! before the next one starts). Frames are 8x8 (16x16 for the engine example's scene) on
//! a scene of four triangles and three lights, which keeps them cheap on lavapipe.
//!
//! The processes run with `MALLOC_ARENA_MAX=1`. With glibc's default, each of lavapipe's
//! rasteriser and queue threads gets a malloc arena of its own, and those arenas grow by
//! up to 8 MiB over the first 20 to 100 frames of `particles_low_res` and
//! `particles_mixed_res`, then hold for good (measured on 5 December: /proc/PID/smaps puts
//! the growth in two 64 MiB-aligned anonymous mappings, heaptrack shows live heap flat over
//! those frames): that is where glibc places the driver's allocations, not memory the
//! program keeps, and it took 100 settling frames before 200 measured ones. In one arena
//! the lowest resident memory of every 10 frames is flat from frame 1 (8 December: every
//! shipped pipeline over 150 frames and the engine example over 300; the most any moved
//! after frame 1 was `msaa_4x_taa`'s 24 KiB between frames 10 and 20), so 20 frames
//! settle it.
//!
//! Resident memory is slow to show a small leak: the leaked blocks first fill the free
//! space the arena already holds resident, megabytes on lavapipe. A leak of 16 KiB a frame
//! (a `vec![1u8; 16 * 1024]` forgotten after each frame) raised the resident floor of only
//! 3 of the 30 pipelines by 1 MiB or more over their 80 frames; and one pipeline's floor
//! rose 0.94 MiB in a run without a leak, hence [`GROWTH_LIMIT`]'s 2 MiB. So the child
//! also reports the live heap (glibc's `mallinfo2`: [`live_heap_bytes`]), which counts a
//! leaked block at once: its lowest of 10 frames moved by at most 6 KiB after frame 20 in
//! any pipeline or the engine example, while a leak of 2 KiB a frame moved it by 0.14 MiB
//! in every pipeline and in the engine example. `rgraph render` tells resident memory
//! only, hence its 1,000 frames: 8 KiB a frame fails it (by 4.7 MiB), 4 KiB does not.
//! Resident memory is still checked in the child: a leak that bypasses malloc (the
//! driver's own mappings, its JIT code) shows only there. The resident checks before this
//! (default arenas, 1 MiB over 200 measured frames) caught the 16 KiB leak in 8 of the 30
//! pipelines, not in the engine example over 1,000 frames, and in `rgraph render` by
//! 10.5 MiB.
//!
//! What that bought (8 December, `time cargo test --test integration -- soak::
//! --test-threads=1` on the 2-core machine, nothing else running): 238.6 s before (each
//! shipped pipeline 100 settling frames and 200 measured, the engine example and `rgraph
//! render` 1,000 frames, the default arenas, resident memory only), 79.9 s after (the
//! shipped pipelines about 45 s, `rgraph render` 23 s, the engine example 10 s); all three
//! at once (`--test-threads=3`) took 62.9 s and held.
//!
//! `RGRAPH_SOAK_FRAMES=N` runs the engine example and `rgraph render` for N frames instead
//! (the long run: `RGRAPH_SOAK_FRAMES=100000 cargo test --release --test integration
//! soak::`).

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;

use rgraph_core::file::{load_file_with, GraphParams, Registry};
use rgraph_core::gpu::{resident_bytes, DeviceObjects, Executor, Gpu, Imports};
use rgraph_core::{CompileOptions, CompiledGraph, Origin, ResourceId};
use rgraph_passes::{FrameInputs, Host, Overrides};
use rgraph_scene::analysis::Features as SceneFeatures;
use rgraph_scene::{Lighting, Scene};
use serde_json::json;

use crate::deferred_support::gpu;
use crate::engine_integration::animate;
use crate::gltf_writer::{temp_dir, Gltf};

/// Frames every shipped pipeline and the engine example run: 20 to settle (frame 0 builds
/// everything; the one arena's lowest may still move by some KiB up to frame 20), then
/// the 80 whose growth is measured. The device objects are compared exactly, so a leaked
/// object fails at any length. Memory is compared between the lowest of frames 20 to 29,
/// 55 to 64 and 90 to 99 (see [`holds`]), 35 frames apart: [`HEAP_GROWTH_LIMIT`] catches
/// a leak of 1 KiB a frame, issue 44's 1.2 MB a frame by some 80 MiB. (300 frames for each
/// pipeline, 100 of them settling, and 1,000 for the engine example made this module a
/// fifth of the suite's test time.)
const SETTLE: usize = 20;
const CHILD_FRAMES: usize = SETTLE + 80;
/// `rgraph render`'s frames without `RGRAPH_SOAK_FRAMES`: only its resident memory tells
/// a leak (see the module's doc), and over 1,000 frames [`GROWTH_LIMIT`] catches 8 KiB a
/// frame.
const RENDER_FRAMES: usize = 1000;
/// The most resident memory may grow over a run's measured frames: twice the most seen
/// without a leak (`deferred_msaa_4x_ssao`'s floor rose 0.94 MiB in one run, its live heap
/// flat: where the one arena placed a block).
const GROWTH_LIMIT: f64 = 2.0 * MIB;
/// The most the live heap ([`live_heap_bytes`]) may grow in each half of a run's measured
/// frames: 8 times the most a floor crept over 80 frames without a leak
/// (`visibility_msaa_4x`'s 8 KiB).
const HEAP_GROWTH_LIMIT: f64 = 32.0 * 1024.0;
const MIB: f64 = 1024.0 * 1024.0;

/// What a process held after one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Sample {
    /// Resident memory in bytes.
    resident: f64,
    /// [`DeviceObjects::objects`] and [`DeviceObjects::bytes`] (`rgraph render` prints the
    /// bytes in tenths of a MiB).
    objects: i64,
    device_bytes: f64,
    /// The heap's live bytes, where the process tells ([`live_heap_bytes`]; `rgraph
    /// render` does not).
    heap: Option<f64>,
}

#[test]
fn every_shipped_pipeline_holds_its_memory() {
    let scene = tiny_scene("soak-pipelines");
    let mut files: Vec<String> = std::fs::read_dir(repo().join("pipelines"))
        .expect("pipelines/ lists")
        .filter_map(|entry| {
            let name = entry.ok()?.file_name().into_string().ok()?;
            name.ends_with(".ron").then_some(name)
        })
        .collect();
    files.sort();
    assert!(files.len() > 20, "pipelines/ holds {} files", files.len());
    // Two processes, each running half the files one after the other: the frames wait on
    // lavapipe's threads about as much as they compute.
    let halves: Vec<Vec<String>> = (0..2)
        .map(|half| files.iter().skip(half).step_by(2).cloned().collect())
        .collect();
    let runs: Vec<Vec<(String, Vec<Sample>)>> = std::thread::scope(|threads| {
        let started: Vec<_> = (halves.iter())
            .map(|half| {
                let run = format!("pipelines:{}", half.join(","));
                let scene = &scene;
                threads.spawn(move || run_child(&run, CHILD_FRAMES, Some(scene)))
            })
            .collect();
        started
            .into_iter()
            .map(|run| run.join().expect("a soak run's thread"))
            .collect()
    });
    let runs: Vec<(String, Vec<Sample>)> = runs.into_iter().flatten().collect();
    let ran: Vec<&str> = runs.iter().map(|(file, _)| file.as_str()).collect();
    let mut expected: Vec<&str> = files.iter().map(String::as_str).collect();
    let mut ran_sorted = ran.clone();
    ran_sorted.sort();
    expected.sort();
    assert_eq!(ran_sorted, expected, "every file in pipelines/ runs once");
    let failures: Vec<String> = (runs.iter())
        .filter_map(|(file, samples)| Some(format!("{file}: {}", holds(samples, SETTLE).err()?)))
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} pipelines did not hold their memory over {} frames:\n{}",
        failures.len(),
        files.len(),
        CHILD_FRAMES - SETTLE,
        failures.join("\n")
    );
}

#[test]
fn rgraph_render_frames_soak_holds_its_memory() {
    let scene = tiny_scene("soak-render");
    let dir = scene.parent().expect("the scene's folder").to_path_buf();
    let frames = soak_frames(RENDER_FRAMES);
    let samples = render_frames("deferred_msaa_4x_tiled.ron", &scene, &dir, frames);
    if let Err(why) = holds(&samples, SETTLE) {
        panic!("rgraph render --frames {frames}: {why}");
    }
}

#[test]
fn engine_example_soak_holds_its_memory() {
    let frames = soak_frames(CHILD_FRAMES);
    let samples = run_child("engine", frames, None).remove(0).1;
    if let Err(why) = holds(&samples, SETTLE) {
        panic!("the engine example over {frames} frames: {why}");
    }
}

/// This test binary run again as a soak's own process: `RGRAPH_SOAK_CHILD` names the
/// run (`engine`, or `pipelines:FILE,FILE,...` on the scene file `RGRAPH_SOAK_SCENE`),
/// `RGRAPH_SOAK_CHILD_FRAMES` its frames, and each frame prints a `SOAK` line for the
/// parent. Without them it does nothing.
#[test]
#[ignore = "a soak's own process, started by the soak tests"]
fn child() {
    let (Ok(run), Ok(frames)) = (
        std::env::var("RGRAPH_SOAK_CHILD"),
        std::env::var("RGRAPH_SOAK_CHILD_FRAMES"),
    ) else {
        return;
    };
    let frames: u32 = frames.parse().expect("a frame count");
    let gpu = gpu();
    let report = |label: &str, index: u32| {
        let device = DeviceObjects::alive(&gpu.device);
        let resident = resident_bytes().expect("/proc/self/status tells resident memory");
        println!(
            "SOAK {label} {index} {resident} {} {} {}",
            device.objects(),
            device.bytes(),
            live_heap_bytes()
        );
    };
    match run.split_once(':') {
        None if run == "engine" => {
            animate(&gpu, frames, (16, 16), |index, _| report("engine", index))
                .expect("the example runs");
        }
        Some(("pipelines", files)) => {
            let scene = std::env::var("RGRAPH_SOAK_SCENE").expect("RGRAPH_SOAK_SCENE");
            let scene = Scene::load(&scene)
                .unwrap_or_else(|e| panic!("{scene} loads: {e}"))
                .lit(Lighting::Both);
            let scene = Arc::new(scene);
            for file in files.split(',') {
                run_pipeline(&gpu, file, &scene, frames, |index| report(file, index));
            }
        }
        _ => panic!("unknown soak run {run:?}"),
    }
}

/// `frames` frames of `file` (in `pipelines/`) drawing `scene` at 8x8 through one
/// executor, compiled as `rgraph render` compiles it (for the scene's features, the
/// final image only where the file has one), the camera orbiting 90 degrees; `each`
/// after each frame.
fn run_pipeline(gpu: &Gpu, file: &str, scene: &Arc<Scene>, frames: u32, each: impl Fn(u32)) {
    let host = Arc::new(Host::new(scene.clone(), Overrides::default()));
    let mut registry = Registry::with_builtins();
    rgraph_passes::register(&mut registry, Some(host.clone()));
    // The generic plugins' demos read their shaders from the shipped shaders/ beside
    // pipelines/, which a graph file reaches only where its host allows it.
    registry
        .allow_graph_root(repo().join("shaders"))
        .expect("shaders/ exists");
    let path = repo().join("pipelines").join(file);
    let mut loaded = load_file_with(&path, &registry, &GraphParams::new())
        .unwrap_or_else(|e| panic!("{file} loads:\n{e}"));
    // The generic plugins' demos have no "color": they run whole.
    if loaded.outputs().contains(&"color") {
        loaded.keep_outputs(&["color"]).expect("color is an output");
    }
    let options = CompileOptions {
        output_size: (8, 8),
        profile: gpu.profile(),
    };
    let features = SceneFeatures::of(scene).names();
    let mut compiled = CompiledGraph::new_for(loaded, &options, &features)
        .unwrap_or_else(|e| panic!("{file} compiles:\n{e}"));
    // The engine's side of what the file imports: a texture as the plan shapes it.
    let targets: Vec<(ResourceId, wgpu::Texture)> = (compiled.plan().resources.iter())
        .filter(|r| r.origin == Origin::Imported && r.lifetime.is_some())
        .map(|r| {
            let shape = r.texture.expect("shipped pipelines import textures only");
            let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(&r.name),
                size: wgpu::Extent3d {
                    width: shape.width,
                    height: shape.height,
                    depth_or_array_layers: shape.layers,
                },
                mip_level_count: shape.mips,
                sample_count: shape.samples,
                dimension: wgpu::TextureDimension::D2,
                format: shape.format,
                usage: r.texture_usage,
                view_formats: &[],
            });
            (r.id, texture)
        })
        .collect();
    let mut imports = Imports::new();
    for (id, texture) in &targets {
        imports.texture(*id, texture);
    }
    let mut executor = Executor::new(gpu);
    let start = FrameInputs::clone(&host.frame());
    let center = scene.bounds.center();
    for index in 0..frames {
        let turn = std::f64::consts::FRAC_PI_2 * f64::from(index) / f64::from(frames);
        let inputs = FrameInputs {
            camera: start.camera.orbited(center, turn),
            ..start.clone()
        };
        host.set_frame(inputs)
            .unwrap_or_else(|e| panic!("{file} frame {index}: {e}"));
        executor
            .execute(&mut compiled, &imports)
            .unwrap_or_else(|e| panic!("{file} frame {index}: {e}"));
        each(index);
    }
}

/// Whether `samples` hold: device objects and their memory the same after every frame
/// from the second on (a pass that builds a pipeline on first need, for a light volume
/// the camera enters, would add one later: these scenes and camera paths need none after
/// the first frame), and the floors of three windows of a tenth of the frames (10 at
/// least: the first from `settle`, the last at the end, one halfway between) rising
/// little: resident memory's by less than [`GROWTH_LIMIT`] from the first to the last,
/// the live heap's (where told) by less than [`HEAP_GROWTH_LIMIT`] in either half. A
/// floor is a window's lowest, because on lavapipe a frame's resident memory moves by up
/// to 3 MiB, and its live heap by up to 8 MiB, with what the driver's threads hold at
/// that moment, where a leak raises the floor. The heap's halves, because a leak raises
/// it in both, where a queue or pool that grows once to a new high (`msaa_4x_taa`'s heap
/// rose 130 KiB once, at frame 5 in one run and after frame 29 in another) raises it in
/// one; resident memory shows a small leak only once the arena's free space is used up
/// (see the module's doc), so it is held over the whole run.
fn holds(samples: &[Sample], settle: usize) -> Result<(), String> {
    let window = (samples.len() / 10).max(10);
    if samples.len() < settle + 2 * window {
        return Err(format!(
            "{} frames reported; expected at least {}",
            samples.len(),
            settle + 2 * window
        ));
    }
    if let Some((index, sample)) = (samples.iter().enumerate().skip(1))
        .find(|(_, s)| (s.objects, s.device_bytes) != (samples[1].objects, samples[1].device_bytes))
    {
        return Err(format!(
            "frame {index} held {} device objects in {:.1} MiB, frame 1 {} in {:.1} MiB",
            sample.objects,
            sample.device_bytes / MIB,
            samples[1].objects,
            samples[1].device_bytes / MIB
        ));
    }
    let starts = [
        settle,
        (settle + samples.len() - window) / 2,
        samples.len() - window,
    ];
    let floors = |amount: fn(&Sample) -> Option<f64>| -> Option<[f64; 3]> {
        let floor = |start: usize| {
            (samples[start..start + window].iter().map(amount))
                .try_fold(f64::MAX, |low, a| Some(low.min(a?)))
        };
        Some([floor(starts[0])?, floor(starts[1])?, floor(starts[2])?])
    };
    let tell = |what: &str, floors: [f64; 3]| {
        let [first, half, last] = floors.map(|f| f / MIB);
        let [from, mid, to] = starts;
        format!(
            "{what} grew by {:.2} MiB, then {:.2} MiB (lowest of {window} frames from frame \
             {from}: {first:.2} MiB, from {mid}: {half:.2} MiB, from {to}: {last:.2} MiB)",
            half - first,
            last - half
        )
    };
    if let Some(resident @ [first, _, last]) = floors(|s| Some(s.resident)) {
        if last - first >= GROWTH_LIMIT {
            return Err(tell("resident memory", resident));
        }
    }
    if let Some(heap @ [first, half, last]) = floors(|s| s.heap) {
        if half - first >= HEAP_GROWTH_LIMIT && last - half >= HEAP_GROWTH_LIMIT {
            return Err(tell("the live heap", heap));
        }
    }
    Ok(())
}

/// `rgraph render --frames FRAMES` of `pipeline` (a file in `pipelines/`) on `scene`, the
/// camera orbiting 90 degrees, at 8x8, the PNGs written in `dir` and deleted after; what
/// its frame lines say it held.
fn render_frames(pipeline: &str, scene: &Path, dir: &Path, frames: usize) -> Vec<Sample> {
    let stem = pipeline.trim_end_matches(".ron");
    let frames_dir = dir.join(stem);
    std::fs::create_dir_all(&frames_dir).expect("a folder for the frames");
    let output = soak_process(env!("CARGO_BIN_EXE_rgraph"))
        .current_dir(repo())
        .args(["render", "--pipeline", &format!("pipelines/{pipeline}")])
        .args(["--scene", scene.to_str().expect("temp paths are UTF-8")])
        .args([
            "--lights", "both", "--width", "8", "--height", "8", "--orbit", "90",
        ])
        .args(["--frames", &frames.to_string(), "--out"])
        .arg(frames_dir.join("f%06d.png"))
        .output()
        .expect("rgraph runs");
    let _ = std::fs::remove_dir_all(&frames_dir);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "rgraph render of {pipeline} failed ({}):\n{stderr}",
        output.status
    );
    let samples: Vec<Sample> = stderr.lines().filter_map(frame_line).collect();
    assert_eq!(
        samples.len(),
        frames,
        "{pipeline}: one frame line with memory per frame expected; stderr:\n{stderr}"
    );
    samples
}

/// A frame line of `rgraph render --frames`: `frame 0012: record+submit 0.4 ms, GPU 1.9
/// ms; resident 103.2 MiB, device 91 objects, 0.6 MiB`.
fn frame_line(line: &str) -> Option<Sample> {
    let rest = line.strip_prefix("frame ")?;
    let resident = rest.split("; resident ").nth(1)?;
    let (resident, device) = resident.split_once(" MiB, device ")?;
    let (objects, bytes) = device.split_once(" objects, ")?;
    Some(Sample {
        resident: resident.parse::<f64>().ok()? * MIB,
        objects: objects.parse().ok()?,
        device_bytes: bytes.strip_suffix(" MiB")?.parse::<f64>().ok()? * MIB,
        heap: None,
    })
}

/// Runs [`child`] in a process of its own for `run` over `frames` frames; its `SOAK`
/// lines by label, in the order the labels first appear.
fn run_child(run: &str, frames: usize, scene: Option<&Path>) -> Vec<(String, Vec<Sample>)> {
    let mut command = soak_process(std::env::current_exe().expect("the test binary's path"));
    command
        .args(["soak::child", "--exact", "--ignored", "--nocapture"])
        .args(["--test-threads", "1"])
        .env("RGRAPH_SOAK_CHILD", run)
        .env("RGRAPH_SOAK_CHILD_FRAMES", frames.to_string());
    if let Some(scene) = scene {
        command.env("RGRAPH_SOAK_SCENE", scene);
    }
    let output = command.output().expect("the test binary runs again");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "the soak run {run} failed ({}):\n{stdout}\n{}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
    let mut runs: Vec<(String, Vec<Sample>)> = Vec::new();
    for line in stdout.lines() {
        // libtest's "test soak::child ... " may open the first line.
        let Some((_, line)) = line.split_once("SOAK ") else {
            continue;
        };
        let fields: Vec<&str> = line.split(' ').collect();
        let number = |i: usize| -> i64 {
            (fields.get(i).and_then(|f| f.parse().ok()))
                .unwrap_or_else(|| panic!("a malformed SOAK line: {line}"))
        };
        let sample = Sample {
            resident: number(2) as f64,
            objects: number(3),
            device_bytes: number(4) as f64,
            heap: Some(number(5) as f64),
        };
        let label = fields[0];
        match runs.iter_mut().find(|(l, _)| l == label) {
            Some((_, samples)) => samples.push(sample),
            None => runs.push((label.to_string(), vec![sample])),
        }
    }
    for (label, samples) in &runs {
        assert_eq!(
            samples.len(),
            frames,
            "{label}: a SOAK line per frame expected"
        );
    }
    runs
}

/// The bytes glibc's malloc has handed out and not had back, in every arena and in
/// chunks of their own mappings (`mallinfo2`'s `uordblks` and `hblkhd`). Unlike resident
/// memory it counts a leaked allocation at once: a leak first fills the free space the
/// arena holds resident (megabytes on lavapipe), which resident memory shows only when
/// it runs out.
fn live_heap_bytes() -> usize {
    // SAFETY: mallinfo2 only reads malloc's own counters, under its locks.
    let info = unsafe { libc::mallinfo2() };
    info.uordblks + info.hblkhd
}

/// A soak's process running `program`, in one malloc arena: see the module's doc.
fn soak_process(program: impl AsRef<OsStr>) -> Command {
    let mut command = Command::new(program);
    command.env("MALLOC_ARENA_MAX", "1");
    command
}

/// `RGRAPH_SOAK_FRAMES`, else `default`.
fn soak_frames(default: usize) -> usize {
    match std::env::var("RGRAPH_SOAK_FRAMES") {
        Ok(text) => text
            .parse()
            .ok()
            .filter(|&n| n >= CHILD_FRAMES)
            .unwrap_or_else(|| {
                panic!("RGRAPH_SOAK_FRAMES={text}: a frame count of {CHILD_FRAMES} or more")
            }),
        Err(_) => default,
    }
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A scene that lights every light path cheaply: a ground quad and a blended quad above
/// it (4 triangles), a directional, a point and a spot light, and a camera looking down
/// at 45 degrees; `--lights both` adds the environment. Written as `test`/tiny.gltf.
fn tiny_scene(test: &str) -> PathBuf {
    let mut gltf = Gltf::default();
    gltf.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    let ground = gltf.push(
        "materials",
        json!({ "pbrMetallicRoughness": { "baseColorFactor": [0.8, 0.7, 0.6, 1.0] } }),
    );
    let glass = gltf.push(
        "materials",
        json!({ "alphaMode": "BLEND",
                "pbrMetallicRoughness": { "baseColorFactor": [0.2, 0.5, 0.9, 0.5] } }),
    );
    for (height, half, material) in [(0.0, 2.0, ground), (0.5, 1.0, glass)] {
        let corners = [[-half, -half], [half, -half], [half, half], [-half, half]];
        let positions = gltf.floats(&corners.map(|[x, z]| [x, height, z]));
        let normals = gltf.floats(&[[0.0f32, 1.0, 0.0]; 4]);
        let indices = gltf.indices_u16(&[0, 2, 1, 0, 3, 2]);
        gltf.mesh(
            "quad",
            json!({ "attributes": { "POSITION": positions, "NORMAL": normals },
                    "indices": indices, "material": material }),
        );
    }
    gltf.json["extensions"] = json!({ "KHR_lights_punctual": { "lights": [
        { "type": "directional", "intensity": 2.0 },
        { "type": "point", "intensity": 20.0, "color": [1.0, 0.8, 0.6] },
        { "type": "spot", "intensity": 30.0, "spot": { "outerConeAngle": 0.6 } },
    ] } });
    // Turns of -45 and -90 degrees about x (x = sin, w = cos of half the angle): the
    // camera and the sun look down at 45 degrees, the spot light straight down.
    let down = json!([-0.382_683_43, 0.0, 0.0, 0.923_879_5]);
    let straight_down = json!([-0.707_106_77, 0.0, 0.0, 0.707_106_77]);
    for (light, placed) in [
        (0, json!({ "rotation": down })),
        (1, json!({ "translation": [0.5, 1.0, 0.5] })),
        (
            2,
            json!({ "translation": [-0.5, 2.0, 0.0], "rotation": straight_down }),
        ),
    ] {
        let mut node = placed;
        node["extensions"] = json!({ "KHR_lights_punctual": { "light": light } });
        gltf.root(node);
    }
    let camera = gltf.push(
        "cameras",
        json!({ "type": "perspective", "perspective": { "yfov": 0.9, "znear": 0.1 } }),
    );
    gltf.root(json!({ "camera": camera, "translation": [0.0, 3.0, 3.0], "rotation": down }));
    let path = temp_dir(test).join("tiny.gltf");
    gltf.write_embedded(&path);
    path
}
