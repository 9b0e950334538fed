//! `rgraph render --animation NAME --time T0..T1 --frames N`: a glTF cube animated across
//! the frame is drawn where the animation puts it at each frame's time, and bad
//! `--animation` / `--time` values are errors that say what is accepted.

use std::path::{Path, PathBuf};

use rgraph_scene::glam::{DVec3, DVec4};
use rgraph_scene::{DepthConvention, Scene};
use serde_json::json;

use crate::cli_support::rgraph;
use crate::gltf_writer::Gltf;

const SIZE: u32 = 64;

/// A unit cube centred on node 0 ("box", at rest at the origin), whose animation "slide"
/// moves it with `interpolation` from x = -3 at 0 s to x = 3 at `end` s, and a second
/// animation "spin" (so the list has two), written as `dir/cube.gltf`.
pub fn sliding_cube(dir: &Path, interpolation: &str, end: f32) -> PathBuf {
    let mut gltf = Gltf::default();
    let corners: Vec<[f32; 3]> = (0..8)
        .map(|i| [i & 1, i >> 1 & 1, i >> 2 & 1].map(|bit| bit as f32 - 0.5))
        .collect();
    let positions = gltf.floats(&corners);
    // Two counter-clockwise triangles per face, seen from outside.
    let faces: [[u16; 4]; 6] = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let indices: Vec<u16> = faces
        .iter()
        .flat_map(|[a, b, c, d]| [*a, *b, *c, *a, *c, *d])
        .collect();
    let indices = gltf.indices_u16(&indices);
    let primitive = json!({ "attributes": { "POSITION": positions }, "indices": indices });
    gltf.push(
        "meshes",
        json!({ "name": "cube", "primitives": [primitive] }),
    );
    gltf.root(json!({ "name": "box", "mesh": 0 }));
    let slide = [[-3.0, 0.0, 0.0], [3.0, 0.0, 0.0]];
    gltf.animation(
        "slide",
        0,
        "translation",
        interpolation,
        &[0.0, end],
        &slide,
    );
    let spin = [[0.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 0.0]];
    gltf.animation("spin", 0, "rotation", "LINEAR", &[0.0, 1.0], &spin);
    let path = dir.join("cube.gltf");
    gltf.write_embedded(&path);
    path
}

/// The alpha-weighted centroid of the image's coverage, in pixels from the top left.
fn coverage_centroid(path: &Path) -> (f64, f64) {
    let image = image::open(path)
        .unwrap_or_else(|e| panic!("{} is not a readable PNG: {e}", path.display()))
        .into_rgba8();
    let (mut sum, mut x, mut y) = (0.0, 0.0, 0.0);
    for (px, py, pixel) in image.enumerate_pixels() {
        let alpha = f64::from(pixel[3]) / 255.0;
        sum += alpha;
        x += (f64::from(px) + 0.5) * alpha;
        y += (f64::from(py) + 0.5) * alpha;
    }
    assert!(sum > 4.0, "{}: nothing drawn", path.display());
    (x / sum, y / sum)
}

/// Where `point` lands in a SIZE x SIZE image of `scene`'s camera, in pixels from the
/// top left.
fn projected(scene: &Scene, point: DVec3) -> (f64, f64) {
    let camera = &scene.camera;
    let projection = camera.projection_matrix(1.0, DepthConvention::Standard);
    let clip = projection.as_dmat4() * camera.view_matrix() * point.extend(1.0);
    let DVec4 { x, y, w, .. } = clip;
    let size = f64::from(SIZE);
    ((x / w + 1.0) * 0.5 * size, (1.0 - y / w) * 0.5 * size)
}

#[test]
fn an_animated_cube_is_drawn_where_its_animation_puts_it_at_each_frame() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let scene_path = sliding_cube(dir.path(), "LINEAR", 2.0);
    let scene_arg = scene_path.to_str().expect("temp paths are UTF-8");
    let pattern = dir.path().join("slide-%04d.png");
    let size = SIZE.to_string();
    #[rustfmt::skip]
    let args = [
        "render", "--scene", scene_arg, "--animation", "slide", "--time", "0.5..1.5",
        "--frames", "2", "--width", &size, "--height", &size, "--background", "transparent",
        "--out", pattern.to_str().expect("temp paths are UTF-8"),
    ];
    let run = rgraph(&args).expect(0);
    run.stderr_has("animation \"slide\" from 0.5 s to 1.5 s");

    let scene = Scene::load(scene_arg).expect("the cube loads");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    // At 0.5 s the cube is a quarter of the way: x = -1.5; at 1.5 s, x = 1.5.
    for (frame, x) in [(0, -1.5), (1, 1.5)] {
        let path = dir.path().join(format!("slide-{frame:04}.png"));
        let (cx, cy) = coverage_centroid(&path);
        let (px, py) = projected(&scene, DVec3::new(x, 0.0, 0.0));
        assert!(
            (cx - px).abs() <= 1.5 && (cy - py).abs() <= 1.5,
            "frame {frame}: the coverage's centroid ({cx:.2}, {cy:.2}) is not within 1.5 \
             pixels of the cube's projected centre ({px:.2}, {py:.2})"
        );
    }
}

/// A point of the default 3 pixels at node 0 ("dot", at rest at the origin), which
/// animation "slide" moves LINEAR from x = -3 at 0 s to x = 3 at 2 s, over a still
/// point at (0, 1, 0) that frames the view with it; written as `dir/dot.gltf`.
fn sliding_point(dir: &Path) -> PathBuf {
    let mut gltf = Gltf::default();
    let moving = gltf.floats(&[[0.0, 0.0, 0.0]]);
    let still = gltf.floats(&[[0.0, 1.0, 0.0]]);
    let points = |positions| json!({ "attributes": { "POSITION": positions }, "mode": 0 });
    gltf.push(
        "meshes",
        json!({ "name": "dot", "primitives": [points(moving)] }),
    );
    gltf.push(
        "meshes",
        json!({ "name": "mark", "primitives": [points(still)] }),
    );
    gltf.root(json!({ "name": "dot", "mesh": 0 }));
    gltf.root(json!({ "name": "mark", "mesh": 1 }));
    let slide = [[-3.0, 0.0, 0.0], [3.0, 0.0, 0.0]];
    gltf.animation("slide", 0, "translation", "LINEAR", &[0.0, 2.0], &slide);
    let path = dir.join("dot.gltf");
    gltf.write_embedded(&path);
    path
}

/// The alpha-weighted centroid of the image's coverage in the rows `rows` (pixels from
/// the top left).
fn centroid_in_rows(path: &Path, rows: std::ops::Range<u32>) -> (f64, f64) {
    let image = image::open(path)
        .unwrap_or_else(|e| panic!("{} is not a readable PNG: {e}", path.display()))
        .into_rgba8();
    let (mut sum, mut x, mut y) = (0.0, 0.0, 0.0);
    for (px, py, pixel) in image.enumerate_pixels() {
        if rows.contains(&py) {
            let alpha = f64::from(pixel[3]) / 255.0;
            sum += alpha;
            x += (f64::from(px) + 0.5) * alpha;
            y += (f64::from(py) + 0.5) * alpha;
        }
    }
    assert!(
        sum > 4.0,
        "{}: nothing drawn in rows {rows:?}",
        path.display()
    );
    (x / sum, y / sum)
}

/// `rgraph render --animation` moves points with their nodes: the sliding point's 3 x 3
/// pixels are centred where the animation puts its node at each frame's time.
#[test]
fn an_animated_point_is_drawn_where_its_animation_puts_it_at_each_frame() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let scene_path = sliding_point(dir.path());
    let scene_arg = scene_path.to_str().expect("temp paths are UTF-8");
    let pattern = dir.path().join("dot-%04d.png");
    let size = SIZE.to_string();
    #[rustfmt::skip]
    let args = [
        "render", "--scene", scene_arg, "--animation", "slide", "--time", "0.5..1.5",
        "--frames", "3", "--width", &size, "--height", &size, "--background", "transparent",
        "--out", pattern.to_str().expect("temp paths are UTF-8"),
    ];
    rgraph(&args).expect(0);
    let scene = Scene::load(scene_arg).expect("the points load");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    // The moving point's row, well below the still one's.
    let (_, row) = projected(&scene, DVec3::ZERO);
    let rows = (row - 4.0) as u32..(row + 4.0) as u32;
    for (frame, x) in [(0, -1.5), (1, 0.0), (2, 1.5)] {
        let path = dir.path().join(format!("dot-{frame:04}.png"));
        let (cx, cy) = centroid_in_rows(&path, rows.clone());
        let (px, py) = projected(&scene, DVec3::new(x, 0.0, 0.0));
        assert!(
            (cx - px).abs() <= 0.5 && (cy - py).abs() <= 0.5,
            "frame {frame}: the point's centroid ({cx:.2}, {cy:.2}) is not within half a \
             pixel of where the animation puts it ({px:.2}, {py:.2})"
        );
    }
}

#[test]
fn an_unknown_animation_is_an_error_listing_the_scene_s_animations() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let scene_path = sliding_cube(dir.path(), "LINEAR", 2.0);
    let scene_arg = scene_path.to_str().expect("temp paths are UTF-8");
    let out = dir.path().join("out.png");
    let out_arg = out.to_str().expect("temp paths are UTF-8");
    let run = rgraph(&[
        "render",
        "--scene",
        scene_arg,
        "--animation",
        "walk",
        "--out",
        out_arg,
    ])
    .expect(1);
    run.stderr_has(&format!(
        "error: scene \"{scene_arg}\" has no animation \"walk\" (its animations: 0 \"slide\", \
         1 \"spin\")"
    ));
    assert!(!out.exists(), "no PNG is written");

    // One frame takes one time, several a span in order.
    rgraph(&[
        "render",
        "--scene",
        scene_arg,
        "--animation",
        "0",
        "--time",
        "0..1",
        "--out",
        out_arg,
    ])
    .expect(2)
    .stderr_has("--time 0..1 is a span, which --frames N above 1 covers");
    let pattern = dir.path().join("f-%04d.png");
    let pattern_arg = pattern.to_str().expect("temp paths are UTF-8");
    #[rustfmt::skip]
    let single = ["render", "--scene", scene_arg, "--animation", "0", "--time", "1", "--frames", "3", "--out", pattern_arg];
    rgraph(&single)
        .expect(2)
        .stderr_has("--frames 3 covers a span of times: give --time T0..T1");
    #[rustfmt::skip]
    let reversed = ["render", "--scene", scene_arg, "--animation", "0", "--time", "2..1", "--frames", "3", "--out", pattern_arg];
    rgraph(&reversed)
        .expect(2)
        .stderr_has("the span 2..1 ends (1 s) before it starts (2 s)");
    rgraph(&["render", "--time", "1", "--out", out_arg])
        .expect(2)
        .stderr_has("--animation");
}
