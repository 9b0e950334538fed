//! One frame's shadow-map work: for each view of the shadow atlas, its tile and, per
//! opaque mesh, the runs of triangles it draws, split into small and large clusters. On
//! a GPU the compute raster (`shadow_raster`) covers both, but for alpha MASK meshes'
//! clusters, which the hardware draws (`shadow_maps`); a CPU adapter's hardware draws
//! them all.
//! Made once per frame, output size, atlas and options by
//! [`GpuScene::shadow_work`](super::GpuScene::shadow_work), and shared by both passes.

use std::ops::Range;
use std::sync::atomic::{AtomicUsize, Ordering};

use super::view_culling::{Fine, Runs};

/// Triangles in one chunk of a run: one compute workgroup's (shadow_compute.wgsl's
/// `ITEM_TRIANGLES`), an invocation a triangle for small clusters.
pub const ITEM_TRIANGLES: u32 = 64;

/// How the views' runs are chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowOptions {
    /// Each view draws only the clusters that may fall inside it (view_culling.rs);
    /// otherwise every mesh whole, all large.
    pub culled: bool,
    /// The most texels a cluster may span to be small (compute), when a compute raster
    /// draws them: `None` leaves every cluster large.
    pub small_texels: Option<f64>,
}

/// The frame's shadow maps, view by view, in view order.
#[derive(Debug)]
pub struct ShadowWork {
    /// By view index: the views' order in the light data and the views' uniform.
    pub views: Vec<ViewWork>,
    /// What the maps show: two frames' works with equal stamps draw the same atlas.
    pub stamp: ShadowStamp,
}

/// Everything a frame's shadow atlas is drawn from, to tell whether the last frame's
/// atlas still holds this frame's maps (`shadow_raster` and `shadow_resolve` keep it
/// then): the views as the GPU reads them (each one's clip space, tile in the atlas and
/// parameters, which follow the camera, the lights and the casters' bounds), the atlas's
/// side and the options, and the count of frames whose casters moved
/// ([`GpuScene`](super::GpuScene)'s frames count a change of any mesh's transform or of
/// the deformation's pose). The scene's geometry is the upload's, the same every frame.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadowStamp {
    pub(super) views: Vec<u8>,
    pub(super) atlas: u32,
    pub(super) options: ShadowOptions,
    pub(super) casters_moved: u64,
}

/// One view: its atlas tile and what it draws.
#[derive(Debug)]
pub struct ViewWork {
    /// x, y and side in texels.
    pub tile: (u32, u32, u32),
    /// The opaque meshes with something to draw here.
    pub meshes: Vec<MeshRuns>,
}

/// One mesh's runs in one view.
#[derive(Debug)]
pub struct MeshRuns {
    /// Its instance index (`Scene::meshes` index).
    pub instance: u32,
    /// Its first index in the scene's index buffer.
    pub first_index: u32,
    /// What its indices add to reach the scene's vertex buffer.
    pub base_vertex: i32,
    /// Alpha MASK: drawn by the hardware's masked pipeline, every run large.
    pub masked: bool,
    /// Triangle ranges from the mesh's first.
    pub runs: Runs,
}

impl MeshRuns {
    /// `range` of the mesh's triangles as a range of the scene's index buffer.
    pub fn indices(&self, range: &Range<u32>) -> Range<u32> {
        self.first_index + 3 * range.start..self.first_index + 3 * range.end
    }
}

impl ShadowWork {
    /// Whether a view draws an alpha MASK mesh: the hardware draws those every frame
    /// (`shadow_maps`), so such a frame's atlas is never kept.
    pub fn draws_masked(&self) -> bool {
        (self.views.iter()).any(|view| view.meshes.iter().any(|mesh| mesh.masked))
    }

    /// The compute raster's runs: every small run, then every large one the hardware
    /// does not draw (all but alpha MASK meshes'), per view, per mesh, in order.
    pub fn raster_runs(&self) -> RasterRuns {
        const NONE: &[Range<u32>] = &[];
        let mut runs = Vec::new();
        let small_chunks = self.push_runs(&mut runs, |mesh| &mesh.runs.small);
        let small = runs.len();
        let large_chunks = self.push_runs(&mut runs, |mesh| match mesh.masked {
            true => NONE,
            false => &mesh.runs.large,
        });
        RasterRuns {
            runs,
            small,
            chunks: [small_chunks, large_chunks],
        }
    }

    /// Appends to `out` the runs `runs` picks of each view's meshes, their first chunks
    /// counted from 0; the chunks they hold.
    fn push_runs(
        &self,
        out: &mut Vec<RasterRun>,
        runs: impl Fn(&MeshRuns) -> &[Range<u32>],
    ) -> u32 {
        let mut chunks = 0;
        for (view, work) in (0u32..).zip(&self.views) {
            for mesh in &work.meshes {
                for run in runs(mesh) {
                    out.push(RasterRun {
                        view,
                        instance: mesh.instance,
                        first_index: mesh.indices(run).start,
                        triangles: run.end - run.start,
                        first_chunk: chunks,
                    });
                    chunks += (run.end - run.start).div_ceil(ITEM_TRIANGLES);
                }
            }
        }
        chunks
    }
}

/// What the compute raster covers of a frame's shadow work
/// ([`ShadowWork::raster_runs`]): its runs, each given out in chunks of
/// [`ITEM_TRIANGLES`] triangles, one a workgroup, by one dispatch for the small runs and
/// one for the large; a workgroup finds its run by the runs' first chunks. A run is 20
/// bytes however many chunks it holds: the 10M-triangle terrain's 22 views are some 8,000
/// runs (160 kB), where a record a chunk was a million (16 MB) to build and upload each
/// frame.
#[derive(Debug)]
pub struct RasterRuns {
    /// The small runs, then the large ones.
    pub runs: Vec<RasterRun>,
    /// How many of `runs` are small.
    pub small: usize,
    /// The chunks of the small runs and of the large ones: each dispatch's workgroups.
    pub chunks: [u32; 2],
}

/// One run as the compute raster reads it (shadow_compute.wgsl's `Run`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct RasterRun {
    /// Its view's index.
    pub view: u32,
    /// Its mesh's instance index.
    pub instance: u32,
    /// Its first triangle's first index in the scene's index buffer.
    pub first_index: u32,
    /// How many triangles it holds.
    pub triangles: u32,
    /// The first of its chunks in its dispatch: the chunks of the runs before it there.
    pub first_chunk: u32,
}

/// Clusters times views past which a frame's views are culled on several threads
/// ([`per_view`]): the 10M-triangle heightfield's 156,000 clusters in 22 views, not the
/// 1M one's 15,600 (1.6 ms on one core here, which two threads on this busy 2-core
/// machine did not make faster: each thread costs some 20 µs to start and needs a core).
pub(super) const PARALLEL_CLUSTERS: usize = 1 << 20;

/// `f` of each view, in order: where `parallel`, on scoped threads (std's: nothing is
/// kept between frames), one a core, each taking the next view not taken; the views'
/// culling is independent. A 10M-triangle heightfield's 22 views took 8 ms to cull on
/// one core of this 2-core machine (`builtin:terrain?cells=2236`, release).
pub(super) fn per_view<V: Sync, W: Send>(
    views: &[V],
    parallel: bool,
    f: impl Fn(&V) -> W + Sync,
) -> Vec<W> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let workers = if parallel { cores.min(views.len()) } else { 1 };
    if workers <= 1 {
        return views.iter().map(f).collect();
    }
    let next = AtomicUsize::new(0);
    let worker = || {
        let mut done = Vec::new();
        loop {
            let i = next.fetch_add(1, Ordering::Relaxed);
            let Some(view) = views.get(i) else {
                return done;
            };
            done.push((i, f(view)));
        }
    };
    let mut done: Vec<(usize, W)> = std::thread::scope(|scope| {
        // The calling thread is one of the workers.
        let others: Vec<_> = (1..workers).map(|_| scope.spawn(worker)).collect();
        let mut done = worker();
        for other in others {
            done.extend(
                other
                    .join()
                    .unwrap_or_else(|e| std::panic::resume_unwind(e)),
            );
        }
        done
    });
    done.sort_by_key(|(i, _)| *i);
    done.into_iter().map(|(_, work)| work).collect()
}

/// What makes a cluster small in a view of `side` texels, given the options.
pub(super) fn fine(options: &ShadowOptions, side: u32, masked: bool) -> Option<Fine> {
    let texels = options.small_texels.filter(|_| !masked && options.culled)?;
    Some(Fine {
        half_side: 0.5 * f64::from(side),
        texels,
    })
}

#[cfg(test)]
// Runs are ranges of triangles: a list of one range is one run, not a range to collect.
#[allow(clippy::single_range_in_vec_init)]
mod tests {
    use super::*;

    fn mesh(instance: u32, first_index: u32, masked: bool, runs: Runs) -> MeshRuns {
        MeshRuns {
            instance,
            first_index,
            base_vertex: 0,
            masked,
            runs,
        }
    }

    /// The compute raster's runs: the small ones of every view, then the large ones but
    /// alpha MASK meshes', each run's first index its first triangle's and its first
    /// chunk the chunks of 64 triangles before it in its dispatch.
    #[test]
    fn raster_runs_count_each_dispatch_s_chunks() {
        let runs = |small: Vec<Range<u32>>, large: Vec<Range<u32>>| Runs { small, large };
        let view = |meshes| ViewWork {
            tile: (0, 0, 1024),
            meshes,
        };
        let work = ShadowWork {
            views: vec![
                view(vec![
                    mesh(2, 300, false, runs(vec![0..10, 100..230], vec![10..100])),
                    mesh(5, 9000, true, runs(vec![], vec![0..64])),
                ]),
                view(vec![mesh(2, 300, false, runs(vec![], vec![0..65]))]),
            ],
            stamp: ShadowStamp {
                views: Vec::new(),
                atlas: 4096,
                options: ShadowOptions {
                    culled: true,
                    small_texels: Some(16.0),
                },
                casters_moved: 0,
            },
        };
        let run = |view, instance, first_index, triangles, first_chunk| RasterRun {
            view,
            instance,
            first_index,
            triangles,
            first_chunk,
        };
        let raster = work.raster_runs();
        assert_eq!(
            raster.runs,
            [
                run(0, 2, 300, 10, 0),
                run(0, 2, 600, 130, 1),
                run(0, 2, 330, 90, 0),
                run(1, 2, 300, 65, 2),
            ]
        );
        assert_eq!((raster.small, raster.chunks), (2, [4, 4]));
    }

    /// Views culled on several threads (each taking a while, so that every thread
    /// takes some) come back in their order, each once.
    #[test]
    fn views_culled_in_parallel_keep_their_order() {
        let views: Vec<u32> = (0..100).collect();
        let expected: Vec<u32> = views.iter().map(|v| 3 * v).collect();
        let cull = |v: &u32| {
            std::thread::sleep(std::time::Duration::from_micros(200));
            3 * v
        };
        for parallel in [false, true] {
            assert_eq!(per_view(&views, parallel, cull), expected);
        }
    }
}
