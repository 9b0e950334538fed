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
    levels: Vec<Vec<Node>>,
    /// Where each cluster's triangles start (from the mesh's first), and after the last
    /// where the last ends: cluster range `a..b` is triangles `starts[a]..starts[b]`.
    starts: Vec<u32>,
}

/// A box of the tree.
#[derive(Clone, Copy, Debug)]
struct Node {
    min: Vec3,
    max: Vec3,
    /// The longest diagonal of the boxes of the clusters it holds: what the widest of
    /// them may span in a view.
    widest: f32,
}

/// A view's runs of one mesh's triangles, from the mesh's first, in order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Runs {
    /// Clusters that lie wholly between the view's depth planes and span at most
    /// [`Fine::texels`] each: few texels a triangle, which the compute raster covers
    /// one invocation a triangle.
    pub small: Vec<Range<u32>>,
    /// The others: for the hardware raster, which clips.
    pub large: Vec<Range<u32>>,
}

/// What makes a cluster small in a view: its map's half side in texels (clip space
/// spans 2 across the map), and the most texels a small cluster's box may span.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fine {
    pub half_side: f64,
    pub texels: f64,
}

impl ClusterBoxes {
    /// The tree over `clusters`, which cover a mesh's triangles in order.
    pub fn new(clusters: &[Cluster]) -> ClusterBoxes {
        let boxes: Vec<Node> = clusters
            .iter()
            .map(|c| {
                let (min, max) = (Vec3::from_array(c.min), Vec3::from_array(c.max));
                Node {
                    min,
                    max,
                    widest: (max - min).length(),
                }
            })
            .collect();
        let mut levels = vec![boxes];
        while levels.last().is_some_and(|level| level.len() > 1) {
            let below = &levels[levels.len() - 1];
            let above: Vec<Node> = below
                .chunks(FAN_OUT)
                .map(|held| {
                    held.iter().fold(held[0], |a, b| Node {
                        min: a.min.min(b.min),
                        max: a.max.max(b.max),
                        widest: a.widest.max(b.widest),
                    })
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

    /// How many clusters the tree is over.
    pub fn clusters(&self) -> usize {
        self.starts.len() - 1
    }

    /// The mesh's triangles that may show in the view `clip_from_world` (wgpu's clip
    /// volume) when the mesh is placed by `world_from_local`, both as the shader has
    /// them (f32), split by `fine` into small and large clusters (all large without):
    /// runs fewer than [`MERGED_GAP`] triangles apart merged.
    pub fn seen(
        &self,
        clip_from_world: DMat4,
        world_from_local: DMat4,
        fine: Option<Fine>,
    ) -> Runs {
        let mut runs = Runs::default();
        let top = self.levels.len() - 1;
        let Some(node) = self.levels[top].first() else {
            return runs;
        };
        let extent = node.min.abs().max(node.max.abs()).as_dvec3();
        let view = MeshInView::new(clip_from_world, world_from_local, extent);
        self.visit(&view, fine, (top, 0), false, &mut runs);
        runs
    }

    /// Visits box `at` of `level`, `inside` the view if a box above it was.
    fn visit(
        &self,
        view: &MeshInView,
        fine: Option<Fine>,
        (level, at): (usize, usize),
        inside: bool,
        runs: &mut Runs,
    ) {
        let node = self.levels[level][at];
        let (min, max) = (node.min.as_dvec3(), node.max.as_dvec3());
        let seen = match inside {
            true => Seen::Inside,
            false => view.test(min, max),
        };
        let inside = match seen {
            Seen::Outside => return,
            Seen::Inside => true,
            Seen::Partly => false,
        };
        // A box partly in view is split down to its clusters, whatever their sizes; one
        // inside is drawn whole where its widest cluster is small, or where there is no
        // telling small ones (`fine`), and split otherwise, its clusters' sizes differing.
        if inside || level == 0 {
            let clusters = FAN_OUT.pow(level as u32);
            let last = self.starts.len() - 1;
            let (a, b) = (at * clusters, ((at + 1) * clusters).min(last));
            let whole = self.starts[a]..self.starts[b];
            let small = fine.is_some_and(|fine| {
                view.texels(min, max, f64::from(node.widest), fine.half_side)
                    .is_some_and(|t| t <= fine.texels)
            });
            if small {
                return push(&mut runs.small, whole);
            }
            if level == 0 || fine.is_none() {
                return push(&mut runs.large, whole);
            }
        }
        let below = self.levels[level - 1].len();
        for child in at * FAN_OUT..((at + 1) * FAN_OUT).min(below) {
            self.visit(view, fine, (level - 1, child), inside, runs);
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
/// the margin by which a box must lie outside it to be culled, and the clip space's x,
/// y and w rows, with the lengths of their first three components.
struct MeshInView {
    planes: [(DVec4, f64); 6],
    rows: [DVec4; 3],
    lengths: [f64; 3],
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
        // A row times the model matrix: the same plane in the mesh's space.
        let local = |plane: DVec4| {
            DVec4::new(
                plane.dot(m.x_axis),
                plane.dot(m.y_axis),
                plane.dot(m.z_axis),
                plane.dot(m.w_axis),
            )
        };
        let planes = world_planes.map(|plane| {
            let margin = ROUNDING * (plane.truncate().abs().dot(reach) + plane.w.abs());
            (local(plane), margin)
        });
        let rows = [local(x), local(y), local(w)];
        MeshInView {
            planes,
            rows,
            lengths: rows.map(|row| row.truncate().length()),
        }
    }

    fn test(&self, min: DVec3, max: DVec3) -> Seen {
        let mut inside = true;
        for (plane, margin) in &self.planes {
            let (near, far) = span(*plane, min, max);
            if far < -margin {
                return Seen::Outside;
            }
            inside &= near > *margin;
        }
        match inside {
            true => Seen::Inside,
            false => Seen::Partly,
        }
    }

    /// The most texels a segment of `length` in the box from `min` to `max` may span in
    /// a map of `half_side` texels a clip unit; `None` where the box does not lie wholly
    /// between the depth planes (the hardware clips there). Inside the box the map
    /// position `x / w` changes by at most `(|row x| + |x| |row w| / w) / w` per unit of
    /// length, bounded by the box's extremes.
    fn texels(&self, min: DVec3, max: DVec3, length: f64, half_side: f64) -> Option<f64> {
        let between = self.planes[4..]
            .iter()
            .all(|(plane, margin)| span(*plane, min, max).0 > *margin);
        let [x, y, w] = self.rows;
        let (w_min, _) = span(w, min, max);
        if !between || w_min <= 0.0 {
            return None;
        }
        let largest = |row: DVec4| {
            let (low, high) = span(row, min, max);
            low.abs().max(high.abs())
        };
        let [x_slope, y_slope, w_slope] = self.lengths;
        let slope =
            |row: DVec4, row_slope: f64| (row_slope + largest(row) * w_slope / w_min) / w_min;
        Some(length * slope(x, x_slope).max(slope(y, y_slope)) * half_side)
    }
}

/// The least and greatest of `dot(row.xyz, p) + row.w` over the box from `min` to `max`.
fn span(row: DVec4, min: DVec3, max: DVec3) -> (f64, f64) {
    let n = row.truncate();
    let high = n.max(DVec3::ZERO) * max + n.min(DVec3::ZERO) * min;
    let low = n.max(DVec3::ZERO) * min + n.min(DVec3::ZERO) * max;
    (low.element_sum() + row.w, high.element_sum() + row.w)
}

#[cfg(test)]
// Runs are ranges of triangles: a list of one range is one run, not a range to collect.
#[allow(clippy::single_range_in_vec_init)]
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
        let seen = boxes.seen(view, DMat4::IDENTITY, None).large;
        assert_eq!(seen, [20..42]);
        // Placed 100 to the left, none shows; 15 to the left, clusters 25 to 35.
        let moved = |x: f64| DMat4::from_translation(DVec3::new(x, 0.0, 0.0));
        let seen = boxes.seen(view, moved(-100.0), None).large;
        assert_eq!(seen, []);
        let seen = boxes.seen(view, moved(-15.0), None).large;
        assert_eq!(seen, [50..72]);
    }

    /// A mesh without triangles shows none.
    #[test]
    fn a_mesh_without_clusters_shows_nothing() {
        let view = DMat4::orthographic_rh(-1.0, 1.0, -1.0, 1.0, -1.0, 1.0);
        assert_eq!(
            ClusterBoxes::new(&[]).seen(view, DMat4::IDENTITY, None),
            Runs::default()
        );
    }

    /// A box that lies outside a plane by less than the rounding margin is kept.
    #[test]
    fn a_box_within_rounding_of_a_plane_is_kept() {
        let clusters = [cluster(0, 1, [0.0; 3], [1.0; 3])];
        let boxes = ClusterBoxes::new(&clusters);
        let view = |left: f64| DMat4::orthographic_rh(left, left + 10.0, -5.0, 5.0, -5.0, 5.0);
        let seen = |left| boxes.seen(view(left), DMat4::IDENTITY, None).large;
        assert_eq!(seen(1.0 + 1e-7), [0..1]);
        assert_eq!(seen(1.01), []);
    }

    /// Clusters spanning at most `Fine::texels` in the map, wholly between its depth
    /// planes, are small; the others large, whatever their size across a depth plane.
    #[test]
    fn clusters_spanning_few_texels_are_small() {
        let clusters: Vec<Cluster> = (0..40)
            .map(|i| cluster(2 * i, 2, [i as f32, 0.0, 0.0], [i as f32 + 1.0, 1.0, 1.0]))
            .collect();
        let boxes = ClusterBoxes::new(&clusters);
        let fine = |texels| {
            Some(Fine {
                half_side: 512.0,
                texels,
            })
        };
        let runs = |small: Vec<Range<u32>>, large: Vec<Range<u32>>| Runs { small, large };
        // A unit is 25.6 texels, a cluster's diagonal (sqrt 3 units) 44.3.
        let view = DMat4::orthographic_rh(0.0, 40.0, -20.0, 20.0, -5.0, 5.0);
        assert_eq!(
            boxes.seen(view, DMat4::IDENTITY, fine(64.0)),
            runs(vec![0..80], vec![])
        );
        assert_eq!(
            boxes.seen(view, DMat4::IDENTITY, fine(32.0)),
            runs(vec![], vec![0..80])
        );
        // The near plane at z = 0.5 cuts every cluster.
        let cut = DMat4::orthographic_rh(0.0, 40.0, -20.0, 20.0, -0.5, 5.0);
        assert_eq!(
            boxes.seen(cut, DMat4::IDENTITY, fine(64.0)),
            runs(vec![], vec![0..80])
        );
        // Seen through a perspective from 10 units away, a cluster spans more near the
        // axis than the bound's worst case allows at 32 texels, less than 1024.
        let eye = DMat4::look_at_rh(
            DVec3::new(20.0, 0.5, 10.0),
            DVec3::new(20.0, 0.5, 0.0),
            DVec3::Y,
        );
        let perspective = DMat4::perspective_rh(2.5, 1.0, 1.0, 100.0) * eye;
        let seen = boxes.seen(perspective, DMat4::IDENTITY, fine(1024.0));
        assert!(seen.large.is_empty() && !seen.small.is_empty(), "{seen:?}");
        let seen = boxes.seen(perspective, DMat4::IDENTITY, fine(32.0));
        assert!(seen.small.is_empty() && !seen.large.is_empty(), "{seen:?}");
    }

    /// The tree's runs are those of deciding every cluster by itself (seen or not,
    /// small or large by its own box), merged alike, though it decides whole boxes at
    /// once: a grid of clusters of two sizes, mixed so that most boxes of the tree hold
    /// both, seen in perspective from above at several places and angles, with several
    /// small sizes, so that some boxes inside the view are small and some split.
    #[test]
    fn the_tree_decides_as_the_clusters_one_by_one() {
        let side = 64;
        let clusters: Vec<Cluster> = (0..side * side)
            .map(|i| {
                let (x, z) = ((i % side) as f32, (i / side) as f32);
                let size = if (i % side + 3 * (i / side)) % 5 == 0 {
                    0.1
                } else {
                    0.9
                };
                cluster(8 * i as u32, 8, [x, 0.0, z], [x + size, 0.1, z + size])
            })
            .collect();
        let boxes = ClusterBoxes::new(&clusters);
        let top = boxes.levels.last().unwrap()[0];
        let extent = top.min.abs().max(top.max.abs()).as_dvec3();
        let one_by_one = |clip_from_world: DMat4, fine: Fine| {
            let view = MeshInView::new(clip_from_world, DMat4::IDENTITY, extent);
            let mut runs = Runs::default();
            for c in &clusters {
                let (min, max) = (Vec3::from_array(c.min), Vec3::from_array(c.max));
                let (low, high) = (min.as_dvec3(), max.as_dvec3());
                if matches!(view.test(low, high), Seen::Outside) {
                    continue;
                }
                let length = f64::from((max - min).length());
                let small = (view.texels(low, high, length, fine.half_side))
                    .is_some_and(|t| t <= fine.texels);
                let runs = if small {
                    &mut runs.small
                } else {
                    &mut runs.large
                };
                push(runs, c.first_triangle..c.first_triangle + c.triangles);
            }
            runs
        };
        let mut decided = [0; 3];
        for (eye, target) in [
            (DVec3::new(32.0, 20.0, 32.0), DVec3::new(32.0, 0.0, 31.0)),
            (DVec3::new(0.0, 6.0, 0.0), DVec3::new(20.0, 0.0, 30.0)),
            (DVec3::new(70.0, 3.0, 20.0), DVec3::new(30.0, 0.0, 40.0)),
        ] {
            let look = DMat4::look_at_rh(eye, target, DVec3::Y);
            let view = DMat4::perspective_rh(1.2, 1.0, 0.5, 200.0) * look;
            for texels in [4.0, 16.0, 64.0] {
                let fine = Fine {
                    half_side: 512.0,
                    texels,
                };
                let tree = boxes.seen(view, DMat4::IDENTITY, Some(fine));
                assert_eq!(tree, one_by_one(view, fine), "from {eye}, {texels} texels");
                decided
                    [usize::from(!tree.small.is_empty()) + usize::from(!tree.large.is_empty())] +=
                    1;
            }
        }
        // Not vacuous: views with both kinds of runs.
        assert!(decided[2] >= 3, "{decided:?}");
    }
}
