//! Which of a mesh's clusters one view can see, on the CPU: the runs of triangles a
//! hardware draw into that view needs, so that a view that sees part of a large mesh
//! (a shadow cascade over a corner of a terrain, a point light's face) draws that part.
//!
//! A view is a clip space, wgpu's clip volume (`-w <= x, y <= w`, `0 <= z <= w`). Its six
//! planes, taken into a mesh's own space through the model matrix (Gribb and Hartmann's
//! extraction from `clip_from_local`), are tested against boxes in the mesh's space: a
//! tree of boxes over its clusters ([`ClusterBoxes`]: each box holds 16 of the level
//! below, the lowest level the clusters' own), so a view that sees a few clusters of a
//! 10M-triangle mesh tests a few hundred boxes, not its 156,000 clusters. A box outside
//! one plane is culled with all it holds; one inside every plane is drawn whole.
//!
//! Culling drops only triangles whose every corner lies outside one plane, which cover
//! no texel of the view: its images are those of drawing everything (tests/culling.rs).
//! The shader computes the corners' clip positions in f32 through the two matrices; the
//! test here is in f64 through their product, and a box counts as outside a plane only
//! by more than a bound on the shader's rounding (below).

use std::ops::Range;

use glam::{DMat4, DVec3, DVec4, Vec3};

use rgraph_scene::Cluster;

/// How many boxes of one level a box of the level above holds.
const FAN_OUT: usize = 16;

/// Runs of seen triangles closer than this are drawn as one, the culled clusters between
/// them with them: a draw costs the CPU about a microsecond to record, which some
/// hundred triangles the raster clips cost the GPU less than. At 1M triangles of
/// builtin:terrain, recording the shadow maps' 16 views took 2.8 ms with only adjacent
/// runs merged (lavapipe, release; 0.3 ms drawing every mesh whole).
const MERGED_GAP: u32 = 4 * 64;

/// The shader's rounding, relative to the magnitudes it sums: f32's is 6e-8 per
/// operation, and a corner's clip position takes some ten operations in sequence; this
/// is 20 times that.
const ROUNDING: f64 = 1e-5;

/// A mesh's clusters' boxes, and boxes over those: `levels[0][i]` holds cluster `i`'s
/// box, `levels[k][i]` the union of `levels[k - 1][16 i .. 16 i + 16]`. The top level
/// has one box, the mesh's.
#[derive(Clone, Debug)]
pub(crate) struct ClusterBoxes {
    levels: Vec<Vec<(Vec3, Vec3)>>,
    /// Where each cluster's triangles start (from the mesh's first), and after the last
    /// where the last ends: cluster range `a..b` is triangles `starts[a]..starts[b]`.
    starts: Vec<u32>,
}

impl ClusterBoxes {
    /// The tree over `clusters`, which cover a mesh's triangles in order.
    pub fn new(clusters: &[Cluster]) -> ClusterBoxes {
        let boxes: Vec<(Vec3, Vec3)> = clusters
            .iter()
            .map(|c| (Vec3::from_array(c.min), Vec3::from_array(c.max)))
            .collect();
        let mut levels = vec![boxes];
        while levels.last().is_some_and(|level| level.len() > 1) {
            let below = &levels[levels.len() - 1];
            let above: Vec<(Vec3, Vec3)> = below
                .chunks(FAN_OUT)
                .map(|held| {
                    held.iter()
                        .fold(held[0], |(min, max), b| (min.min(b.0), max.max(b.1)))
                })
                .collect();
            levels.push(above);
        }
        let mut starts: Vec<u32> = clusters.iter().map(|c| c.first_triangle).collect();
        starts.push(
            clusters
                .last()
                .map_or(0, |c| c.first_triangle + c.triangles),
        );
        ClusterBoxes { levels, starts }
    }

    /// The mesh's triangles that may show in the view `clip_from_world` (wgpu's clip
    /// volume) when the mesh is placed by `world_from_local`, both as the shader has
    /// them (f32): ranges of triangles from the mesh's first, in order, ranges fewer
    /// than [`MERGED_GAP`] triangles apart merged.
    pub fn seen(&self, clip_from_world: DMat4, world_from_local: DMat4) -> Vec<Range<u32>> {
        let mut seen = Vec::new();
        let top = self.levels.len() - 1;
        let Some(&(min, max)) = self.levels[top].first() else {
            return seen;
        };
        let extent = min.abs().max(max.abs()).as_dvec3();
        let view = MeshInView::new(clip_from_world, world_from_local, extent);
        self.visit(&view, top, 0, &mut seen);
        seen
    }

    fn visit(&self, view: &MeshInView, level: usize, at: usize, seen: &mut Vec<Range<u32>>) {
        let (min, max) = self.levels[level][at];
        match view.test(min.as_dvec3(), max.as_dvec3()) {
            Seen::Outside => {}
            Seen::Inside => {
                let clusters = FAN_OUT.pow(level as u32);
                let last = self.starts.len() - 1;
                let (a, b) = (at * clusters, ((at + 1) * clusters).min(last));
                push(seen, self.starts[a]..self.starts[b]);
            }
            Seen::Partly if level == 0 => push(seen, self.starts[at]..self.starts[at + 1]),
            Seen::Partly => {
                let below = self.levels[level - 1].len();
                for child in at * FAN_OUT..((at + 1) * FAN_OUT).min(below) {
                    self.visit(view, level - 1, child, seen);
                }
            }
        }
    }
}

/// `range` after the ranges in `seen`, merged into the last where fewer than
/// [`MERGED_GAP`] triangles lie between them.
fn push(seen: &mut Vec<Range<u32>>, range: Range<u32>) {
    match seen.last_mut() {
        Some(last) if range.start - last.end < MERGED_GAP => last.end = range.end,
        _ => seen.push(range),
    }
}

/// What a box is to a view.
enum Seen {
    /// Outside one of its planes: nothing in it shows.
    Outside,
    /// Inside all of them.
    Inside,
    Partly,
}

/// A view's clip volume in one mesh's space: six planes `dot(n, p) + d >= 0`, each with
/// the margin by which a box must lie outside it to be culled.
struct MeshInView {
    planes: [(DVec4, f64); 6],
}

impl MeshInView {
    /// The view `clip_from_world` (wgpu's clip volume) in the space of a mesh placed by
    /// `world_from_local`, whose vertices lie within `extent` of its origin on each
    /// axis: matrices as the shader has them (f32), multiplied here in f64.
    fn new(clip_from_world: DMat4, world_from_local: DMat4, extent: DVec3) -> MeshInView {
        let row = |i: usize| clip_from_world.row(i);
        let (x, y, z, w) = (row(0), row(1), row(2), row(3));
        let world_planes = [w + x, w - x, w + y, w - y, z, w - z];
        // How large a world position's coordinates may be: what the shader's rounding
        // of `world_from_local * p` is relative to.
        let m = world_from_local;
        let reach = DVec3::new(
            m.row(0).truncate().abs().dot(extent) + m.row(0).w.abs(),
            m.row(1).truncate().abs().dot(extent) + m.row(1).w.abs(),
            m.row(2).truncate().abs().dot(extent) + m.row(2).w.abs(),
        );
        let planes = world_planes.map(|plane| {
            let margin = ROUNDING * (plane.truncate().abs().dot(reach) + plane.w.abs());
            // A plane's row times the model matrix: the same plane in the mesh's space.
            let local = DVec4::new(
                plane.dot(m.x_axis),
                plane.dot(m.y_axis),
                plane.dot(m.z_axis),
                plane.dot(m.w_axis),
            );
            (local, margin)
        });
        MeshInView { planes }
    }

    fn test(&self, min: DVec3, max: DVec3) -> Seen {
        let mut inside = true;
        for (plane, margin) in &self.planes {
            let n = plane.truncate();
            // The box's corners farthest along the plane's normal and against it.
            let far = n.max(DVec3::ZERO) * max + n.min(DVec3::ZERO) * min;
            let near = n.max(DVec3::ZERO) * min + n.min(DVec3::ZERO) * max;
            if far.element_sum() + plane.w < -margin {
                return Seen::Outside;
            }
            inside &= near.element_sum() + plane.w > *margin;
        }
        match inside {
            true => Seen::Inside,
            false => Seen::Partly,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cluster(first_triangle: u32, triangles: u32, min: [f32; 3], max: [f32; 3]) -> Cluster {
        Cluster {
            first_triangle,
            triangles,
            min,
            max,
            center: [0.0; 3],
            radius: 0.0,
            cone_axis: [0.0; 3],
            cone_cutoff: 1.0,
        }
    }

    /// A row of 40 unit clusters along x, 2 triangles each, through an orthographic view
    /// of x in [10.5, 20.5]: the clusters from 10 to 20 show, as triangles 20 to 42.
    #[test]
    fn a_view_sees_the_clusters_it_crosses_in_one_run() {
        let clusters: Vec<Cluster> = (0..40)
            .map(|i| cluster(2 * i, 2, [i as f32, 0.0, 0.0], [i as f32 + 1.0, 1.0, 1.0]))
            .collect();
        let boxes = ClusterBoxes::new(&clusters);
        assert_eq!(
            boxes.levels.iter().map(Vec::len).collect::<Vec<_>>(),
            [40, 3, 1]
        );
        let view = DMat4::orthographic_rh(10.5, 20.5, -5.0, 5.0, -5.0, 5.0);
        let seen = boxes.seen(view, DMat4::IDENTITY);
        assert_eq!(seen, [20..42]);
        // Placed 100 to the left, none shows; 15 to the left, clusters 25 to 35.
        let moved = |x: f64| DMat4::from_translation(DVec3::new(x, 0.0, 0.0));
        let seen = boxes.seen(view, moved(-100.0));
        assert_eq!(seen, []);
        let seen = boxes.seen(view, moved(-15.0));
        assert_eq!(seen, [50..72]);
    }

    /// A mesh without triangles shows none.
    #[test]
    fn a_mesh_without_clusters_shows_nothing() {
        let view = DMat4::orthographic_rh(-1.0, 1.0, -1.0, 1.0, -1.0, 1.0);
        assert_eq!(ClusterBoxes::new(&[]).seen(view, DMat4::IDENTITY), []);
    }

    /// A box that lies outside a plane by less than the rounding margin is kept.
    #[test]
    fn a_box_within_rounding_of_a_plane_is_kept() {
        let clusters = [cluster(0, 1, [0.0; 3], [1.0; 3])];
        let boxes = ClusterBoxes::new(&clusters);
        let view = |left: f64| DMat4::orthographic_rh(left, left + 10.0, -5.0, 5.0, -5.0, 5.0);
        let seen = |left| boxes.seen(view(left), DMat4::IDENTITY);
        assert_eq!(seen(1.0 + 1e-7), [0..1]);
        assert_eq!(seen(1.01), []);
    }
}
