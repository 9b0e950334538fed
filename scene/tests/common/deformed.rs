//! Three tiny deformed models, built in code: a skinned strip that bends at a joint, a
//! strip whose every vertex hangs on eight joints (JOINTS_0 and JOINTS_1), and a morphed
//! quad whose top edge a morph target lifts.

use serde_json::json;

use super::{Gltf, FLOAT, UNSIGNED_SHORT};

/// [`eight_joint_strip`]'s joints at rest: translation and rotation (x, y, z, w) of the
/// root nodes 0 to 7. Joints 4 to 7 (JOINTS_1) move the strip as much as 0 to 3 do.
pub const EIGHT_JOINTS: [([f32; 3], [f32; 4]); 8] = [
    ([0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]),
    ([0.0, 0.1, 0.0], [0.0, 0.0, 0.0, 1.0]),
    ([0.0, -0.1, 0.0], [0.0, 0.0, 0.0, 1.0]),
    ([0.1, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]),
    ([0.0, 0.3, 0.0], [0.0, 0.0, 0.0, 1.0]),
    // 10° about +Z.
    ([0.0, 0.0, 0.0], [0.0, 0.0, 0.087_155_74, 0.996_194_7]),
    // 20° about +Y.
    ([0.0, 0.0, 0.2], [0.0, 0.173_648_18, 0.0, 0.984_807_7]),
    ([-0.2, 0.2, 0.0], [0.0, 0.0, 0.0, 1.0]),
];

/// [`eight_joint_strip`]'s columns of vertices: x from 0 to 2 in eight steps.
pub const EIGHT_COLUMNS: usize = 9;

/// The weights of joints 0 to 7 of [`eight_joint_strip`]'s vertices in column `column`:
/// (1 + (joint + column) mod 4) / 20, half of them on joints 4 to 7.
pub fn eight_weights(column: usize) -> [f32; 8] {
    std::array::from_fn(|joint| (1 + (joint + column) % 4) as f32 / 20.0)
}

/// A strip from x = 0 to 2, y from -0.25 to 0.25 (normals +Z), in [`EIGHT_COLUMNS`]
/// columns of two vertices, skinned to eight joints: the root nodes 0 to 7 posed as
/// [`EIGHT_JOINTS`] says (no inverse bind matrices: the identity), every vertex on all
/// eight with [`eight_weights`], joints 0 to 3 in JOINTS_0 and WEIGHTS_0 and 4 to 7 in
/// JOINTS_1 and WEIGHTS_1; node 8 "strip" places it with skin 0 "eight". Animation 0,
/// "sway", turns joint 5 from 10° to 30° about +Z over 1 s (LINEAR).
pub fn eight_joint_strip() -> Gltf {
    let mut gltf = Gltf::default();
    let vertices = 2 * EIGHT_COLUMNS;
    let corners: Vec<[f32; 3]> = (0..EIGHT_COLUMNS)
        .flat_map(|c| {
            let x = 2.0 * c as f32 / (EIGHT_COLUMNS - 1) as f32;
            [[x, -0.25, 0.0], [x, 0.25, 0.0]]
        })
        .collect();
    let positions = gltf.floats(&corners);
    let normals = gltf.floats(&vec![[0.0, 0.0, 1.0]; vertices]);
    let mut attributes = json!({ "POSITION": positions, "NORMAL": normals });
    for set in 0..2 {
        let ids: Vec<u8> = std::iter::repeat_n([0u16, 1, 2, 3].map(|j| j + 4 * set), vertices)
            .flatten()
            .flat_map(|j| j.to_le_bytes())
            .collect();
        let joints = gltf.accessor(&ids, UNSIGNED_SHORT, vertices, "VEC4", false);
        let weights: Vec<[f32; 4]> = (0..vertices)
            .map(|v| {
                let all = eight_weights(v / 2);
                std::array::from_fn(|k| all[4 * set as usize + k])
            })
            .collect();
        let weights = gltf.floats(&weights);
        attributes[format!("JOINTS_{set}")] = json!(joints);
        attributes[format!("WEIGHTS_{set}")] = json!(weights);
    }
    let indices: Vec<u16> = (0..EIGHT_COLUMNS as u16 - 1)
        .flat_map(|c| {
            let (a, b) = (2 * c, 2 * c + 2);
            [a, b, b + 1, a, b + 1, a + 1]
        })
        .collect();
    let indices = gltf.indices_u16(&indices);
    let primitive = json!({ "attributes": attributes, "indices": indices });
    let mesh = gltf.push(
        "meshes",
        json!({ "name": "eight", "primitives": [primitive] }),
    );
    for (joint, (translation, rotation)) in EIGHT_JOINTS.iter().enumerate() {
        gltf.root(
            json!({ "name": format!("joint {joint}"), "translation": translation,
                          "rotation": rotation }),
        );
    }
    gltf.push(
        "skins",
        json!({ "name": "eight", "joints": [0, 1, 2, 3, 4, 5, 6, 7] }),
    );
    gltf.root(json!({ "name": "strip", "mesh": mesh, "skin": 0 }));
    let turn = |degrees: f32| {
        let half = degrees.to_radians() / 2.0;
        [0.0, 0.0, half.sin(), half.cos()]
    };
    gltf.animation(
        "sway",
        5,
        "rotation",
        "LINEAR",
        &[0.0, 1.0],
        &[turn(10.0), turn(30.0)],
    );
    gltf
}

/// The x of [`bent_strip`]'s three pairs of vertices: its left end, its middle, its
/// right end.
pub const STRIP_X: [f32; 3] = [0.0, 1.0, 2.0];

/// A strip from x = 0 to 2, y from -0.25 to 0.25 (normals +Z), skinned to two joints:
/// node 0 "root" at the origin (joint 0), its child node 1 "bend" at x = 1 (joint 1)
/// turned 90° about +Y at rest, and node 2 "strip", a root node placing the mesh with
/// the skin, translated by (5, 0, 0) (which skinning ignores, as glTF says). The left
/// end's vertices hang on joint 0, the middle ones half on each, the right end's on
/// joint 1. Inverse bind matrices undo the joints' bind positions (x = 0 and x = 1).
/// Animation 0, "bend", turns "bend" from 0° at 0 s to 90° at 1 s about +Y (LINEAR).
pub fn bent_strip() -> Gltf {
    let mut gltf = Gltf::default();
    let corners: Vec<[f32; 3]> = (STRIP_X.iter())
        .flat_map(|&x| [[x, -0.25, 0.0], [x, 0.25, 0.0]])
        .collect();
    let positions = gltf.floats(&corners);
    let normals = gltf.floats(&[[0.0, 0.0, 1.0]; 6]);
    let joints: Vec<u8> = [[0u16, 1, 0, 0]; 6]
        .iter()
        .flatten()
        .flat_map(|j| j.to_le_bytes())
        .collect();
    let joints = gltf.accessor(&joints, UNSIGNED_SHORT, 6, "VEC4", false);
    let weights = gltf.floats(&[
        [1.0, 0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0, 0.0],
        [0.5, 0.5, 0.0, 0.0],
        [0.5, 0.5, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
    ]);
    let indices = gltf.indices_u16(&[0, 2, 3, 0, 3, 1, 2, 4, 5, 2, 5, 3]);
    let primitive = json!({
        "attributes": { "POSITION": positions, "NORMAL": normals, "JOINTS_0": joints, "WEIGHTS_0": weights },
        "indices": indices,
    });
    let mesh = gltf.push(
        "meshes",
        json!({ "name": "strip", "primitives": [primitive] }),
    );
    let inverse_binds: Vec<u8> = [0.0f32, -1.0]
        .iter()
        .flat_map(|&x| {
            let mut m = [0.0f32; 16];
            (m[0], m[5], m[10], m[15], m[12]) = (1.0, 1.0, 1.0, 1.0, x);
            m
        })
        .flat_map(f32::to_le_bytes)
        .collect();
    let inverse_binds = gltf.accessor(&inverse_binds, FLOAT, 2, "MAT4", false);
    let h = std::f32::consts::FRAC_1_SQRT_2;
    gltf.root(json!({ "name": "root", "children": [1] }));
    gltf.push(
        "nodes",
        json!({ "name": "bend", "translation": [1.0, 0.0, 0.0], "rotation": [0.0, h, 0.0, h] }),
    );
    gltf.push(
        "skins",
        json!({ "name": "arm", "joints": [0, 1], "inverseBindMatrices": inverse_binds }),
    );
    gltf.root(json!({ "name": "strip", "mesh": mesh, "skin": 0, "translation": [5.0, 0.0, 0.0] }));
    gltf.animation(
        "bend",
        1,
        "rotation",
        "LINEAR",
        &[0.0, 1.0],
        &[[0.0, 0.0, 0.0, 1.0], [0.0, h, 0.0, h]],
    );
    gltf
}

/// A unit quad in the XY plane (normals +Z) whose one morph target lifts its top edge
/// by 0.5 along +Y and tilts its normals towards +X by 0.5, weighted 0.25 by default
/// (the mesh's `weights`); node 0 "quad" places it. Animation 0, "grow", drives the
/// weight with `interpolation` over keys at 0, 1 and 2 s: 0, 1, 0.5 (for CUBICSPLINE,
/// zero tangents).
pub fn morphed_quad(interpolation: &str) -> Gltf {
    let mut gltf = Gltf::default();
    let positions = gltf.floats(&[
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ]);
    let normals = gltf.floats(&[[0.0, 0.0, 1.0]; 4]);
    let lift = gltf.floats(&[
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0],
        [0.0, 0.5, 0.0],
        [0.0, 0.5, 0.0],
    ]);
    let tilt = gltf.floats(&[
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0],
        [0.5, 0.0, 0.0],
        [0.5, 0.0, 0.0],
    ]);
    let indices = gltf.indices_u16(&[0, 1, 2, 0, 2, 3]);
    let primitive = json!({
        "attributes": { "POSITION": positions, "NORMAL": normals },
        "targets": [{ "POSITION": lift, "NORMAL": tilt }],
        "indices": indices,
    });
    gltf.mesh("quad", primitive);
    gltf.json["meshes"][0]["weights"] = json!([0.25]);
    gltf.json["nodes"][0]["name"] = json!("quad");
    let times = [0.0, 1.0, 2.0];
    match interpolation {
        "CUBICSPLINE" => {
            let values = [0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.5, 0.0].map(|w| [w]);
            gltf.animation("grow", 0, "weights", interpolation, &times, &values)
        }
        _ => gltf.animation(
            "grow",
            0,
            "weights",
            interpolation,
            &times,
            &[[0.0], [1.0], [0.5]],
        ),
    };
    gltf
}
