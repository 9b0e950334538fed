//! Points and lines: glTF primitives of modes POINTS, LINES, LINE_LOOP and LINE_STRIP,
//! which no surface pass draws (they have no area): the `points_lines` pass draws them
//! after the opaque scene is lit.

use glam::{DMat4, DVec3, Vec3};

use super::bounds::Aabb;

/// What a [`PointsLines`] draws with its indices.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Topology {
    /// One index per point.
    Points,
    /// Two indices per segment (LINE_LOOP and LINE_STRIP are loaded as such lists).
    Lines,
}

/// A primitive of points or line segments with one material, drawn unlit as the glTF
/// sample viewer draws them: base colour factor times vertex colour, plus emission.
///
/// Contract: `colors` is as long as `positions`, every index is `< positions.len()`, and
/// [`Topology::Lines`] has an even number of indices. Like [`Mesh`](crate::Mesh), vertex
/// data stays in object space and `transform` (f64) places it at rest; in a frame, the
/// pose's transform for it ([`Pose::points_lines`](crate::Pose::points_lines): where the
/// animations put the node placing it) does. Skins and morph targets do not deform it.
#[derive(Clone, Debug, PartialEq)]
pub struct PointsLines {
    /// `mesh name/primitive index` for glTF.
    pub name: String,
    /// How the indices are read.
    pub topology: Topology,
    /// Object-space positions.
    pub positions: Vec<[f32; 3]>,
    /// COLOR_0 as linear RGBA, one per position; white where the source has none.
    pub colors: Vec<[f32; 4]>,
    /// Points, or segments as pairs, indexing `positions`.
    pub indices: Vec<u32>,
    /// Index into `Scene::materials`.
    pub material: usize,
    /// Object space to world space at rest.
    pub transform: DMat4,
}

impl PointsLines {
    /// World-space positions at rest of the vertices the indices use.
    pub fn world_positions(&self) -> impl Iterator<Item = DVec3> + '_ {
        self.indices.iter().map(|&i| {
            let position = Vec3::from_array(self.positions[i as usize]).as_dvec3();
            self.transform.transform_point3(position)
        })
    }

    /// Exact world-space bounds of the points or segments at rest, `None` without
    /// indices.
    pub fn world_bounds(&self) -> Option<Aabb> {
        Aabb::from_points(self.world_positions())
    }

    /// Object-space bounds of the points or segments, `None` without indices: what any
    /// transform of a pose (`Pose::points_lines`) places.
    pub fn object_bounds(&self) -> Option<Aabb> {
        let positions = self.indices.iter();
        Aabb::from_points(
            positions.map(|&i| Vec3::from_array(self.positions[i as usize]).as_dvec3()),
        )
    }

    /// Points, or segments: what one draw of them rasterises.
    pub fn count(&self) -> usize {
        match self.topology {
            Topology::Points => self.indices.len(),
            Topology::Lines => self.indices.len() / 2,
        }
    }
}
