//! What a built-in scene of a given size will hold, counted from its size parameter before
//! anything is built, against the scene limits: [`MAX_MESHES`] and
//! [`DEFAULT_MAX_SCENE_BYTES`] (4 GiB) of vertices and indices, the limit a glTF scene is held to as well (with the meshes' own
//! records counted too: a scene of a million small meshes spends a fifth of its memory on
//! them). The scale scenes
//! (`terrain`, `city`) derive the largest value of their size parameter from it, so the
//! parameter's range check is the memory check and fails before the first allocation.

use crate::{Mesh, Vertex, DEFAULT_MAX_SCENE_BYTES, MAX_MESHES};

/// Vertices, indices and meshes of a scene (or a part of one), counted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Geometry {
    pub vertices: u64,
    pub indices: u64,
    pub meshes: u64,
}

impl Geometry {
    /// `self` and `other` together.
    pub const fn plus(self, other: Geometry) -> Geometry {
        Geometry {
            vertices: self.vertices + other.vertices,
            indices: self.indices + other.indices,
            meshes: self.meshes + other.meshes,
        }
    }

    /// `count` copies of `self`.
    pub const fn times(self, count: u64) -> Geometry {
        Geometry {
            vertices: self.vertices * count,
            indices: self.indices * count,
            meshes: self.meshes * count,
        }
    }

    /// What it takes in memory: a [`Vertex`] and a `u32` index each, as the glTF loader
    /// counts a primitive, and a [`Mesh`] each (not counting its name).
    pub const fn bytes(self) -> u64 {
        self.vertices * std::mem::size_of::<Vertex>() as u64
            + self.indices * 4
            + self.meshes * std::mem::size_of::<Mesh>() as u64
    }

    /// Whether it fits the scene limits: bytes and meshes.
    pub const fn fits(self) -> bool {
        self.bytes() <= DEFAULT_MAX_SCENE_BYTES && self.meshes <= MAX_MESHES as u64
    }
}

#[cfg(test)]
mod tests {
    use super::Geometry;

    #[test]
    fn bytes_are_56_per_vertex_4_per_index_and_176_per_mesh() {
        let quad = Geometry {
            vertices: 4,
            indices: 6,
            meshes: 1,
        };
        assert_eq!(quad.bytes(), 4 * 56 + 6 * 4 + 176);
        assert_eq!(quad.times(3).plus(quad).bytes(), 4 * quad.bytes());
        let limit = Geometry {
            vertices: 0,
            indices: 1 << 30,
            meshes: 0,
        };
        assert!(limit.fits());
        let one = Geometry {
            vertices: 0,
            indices: 1,
            meshes: 0,
        };
        assert!(!limit.plus(one).fits());
    }
}
