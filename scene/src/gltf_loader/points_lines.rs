//! Point and line primitives (modes POINTS, LINES, LINE_LOOP, LINE_STRIP) to
//! [`PointsLines`]: POSITION and COLOR_0 (every other attribute is ignored: they are drawn
//! unlit and untextured), with loops and strips converted to segment lists.
//!
//! They move with the nodes placing them (the node tree places them as it places meshes),
//! but are not deformed: a skin on their node and their morph targets are ignored with a
//! warning. Skinned or morphed point clouds are rare, and deforming them would take a
//! deformation pass of their own (the scene's moves the triangle meshes' shared vertex
//! buffer, which they are not in).

use glam::DMat4;
use gltf::mesh::{Mode, Semantic};

use super::site::Site;
use super::{accessor, Loader};
use crate::error::label;
use crate::{PointsLines, SceneError, Topology};

impl Loader<'_> {
    /// Converts one point or line primitive of a mesh placed at `world` and adds it to the
    /// scene. Fails, naming the file, mesh, primitive and accessor, on an index past the
    /// vertices or a LINES primitive with an odd number of indices.
    pub(super) fn points_lines(
        &mut self,
        mesh: &gltf::Mesh,
        primitive: &gltf::Primitive,
        world: DMat4,
    ) -> Result<(), SceneError> {
        let site = Site {
            file: self.file,
            mesh: label("mesh", mesh.index(), mesh.name()),
            primitive: primitive.index(),
        };
        let positions = self
            .attribute::<3>(&site, primitive, Semantic::Positions, "POSITION")?
            .ok_or_else(|| site.invalid("has no POSITION attribute".to_owned()))?;
        let colors = self.colors(&site, primitive)?;
        site.check_finite(&positions, None, None, None, colors.as_deref(), None)?;
        // What the list is read from, for the errors about its length.
        let (indices, source) = match primitive.indices() {
            Some(accessor) => (
                accessor::read_indices(&self.buffers, &accessor)
                    .map_err(|reason| site.accessor_error("indices", &accessor, reason))?,
                ("indices", accessor),
            ),
            None => {
                let accessor = primitive.get(&Semantic::Positions).expect("read above");
                (
                    (0..positions.len() as u32).collect(),
                    ("POSITION", accessor),
                )
            }
        };
        // The budget took this primitive's bytes before anything was built (see `reserve`).
        site.check_indices(&indices, positions.len())?;
        let (topology, indices) = segment_list(primitive.mode(), indices)
            .map_err(|reason| site.accessor_error(source.0, &source.1, reason))?;
        let material = self.material(&primitive.material())?;
        self.builder.points_lines.push(PointsLines {
            name: format!("{} primitive {}", site.mesh, site.primitive),
            topology,
            colors: colors.unwrap_or_else(|| vec![[1.0; 4]; positions.len()]),
            positions,
            indices,
            material,
            transform: world,
        });
        Ok(())
    }
}

impl Loader<'_> {
    /// Warns, once per primitive and node, when `primitive` (of points or lines) of `mesh`
    /// would be deformed: `node` places it with a skin, or it has morph targets. It is
    /// drawn undeformed where `node` puts it.
    pub(super) fn undeformed_points_lines(
        &mut self,
        mesh: &gltf::Mesh,
        primitive: &gltf::Primitive,
        node: &gltf::Node,
    ) {
        let skin = node
            .skin()
            .map(|skin| label("skin", skin.index(), skin.name()));
        let targets = primitive.morph_targets().len();
        let ignored = match (skin, targets) {
            (None, 0) => return,
            (Some(skin), 0) => format!("{skin} (its JOINTS_0 and WEIGHTS_0) is"),
            (None, n) => format!("its {n} morph targets are"),
            (Some(skin), n) => {
                format!("{skin} (its JOINTS_0 and WEIGHTS_0) and its {n} morph targets are")
            }
        };
        let warning = format!(
            "{} primitive {}: points and lines are not deformed: {ignored} ignored, and they \
             follow the transform of {}",
            label("mesh", mesh.index(), mesh.name()),
            primitive.index(),
            label("node", node.index(), node.name()),
        );
        if !self.builder.warnings.contains(&warning) {
            self.builder.warnings.push(warning);
        }
    }
}

/// The points of a POINTS primitive, or the segments of a line mode as a list of pairs:
/// LINE_STRIP joins each vertex to the next, LINE_LOOP the last to the first too (a loop
/// or strip of one vertex has no segment). Fails on LINES with an odd count.
fn segment_list(mode: Mode, indices: Vec<u32>) -> Result<(Topology, Vec<u32>), String> {
    let n = indices.len();
    let strip = |indices: &[u32]| -> Vec<u32> { indices.windows(2).flatten().copied().collect() };
    match mode {
        Mode::Points => Ok((Topology::Points, indices)),
        Mode::Lines if n.is_multiple_of(2) => Ok((Topology::Lines, indices)),
        Mode::Lines => Err(format!(
            "LINES needs an even number of indices (two per segment), has {n}"
        )),
        Mode::LineStrip => Ok((Topology::Lines, strip(&indices))),
        Mode::LineLoop => {
            let mut list = strip(&indices);
            if n >= 2 {
                list.extend([indices[n - 1], indices[0]]);
            }
            Ok((Topology::Lines, list))
        }
        other => Err(format!("mode {other:?} is not a point or line mode")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loops_and_strips_become_segment_lists() {
        let list = |mode| segment_list(mode, vec![4, 5, 6]).unwrap();
        assert_eq!(list(Mode::LineStrip), (Topology::Lines, vec![4, 5, 5, 6]));
        assert_eq!(
            list(Mode::LineLoop),
            (Topology::Lines, vec![4, 5, 5, 6, 6, 4])
        );
        assert_eq!(list(Mode::Points), (Topology::Points, vec![4, 5, 6]));
        assert_eq!(
            segment_list(Mode::LineLoop, vec![7]).unwrap().1,
            Vec::<u32>::new()
        );
        assert!(segment_list(Mode::Lines, vec![1, 2, 3]).is_err());
    }
}
