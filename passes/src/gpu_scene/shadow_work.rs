//! One frame's shadow-map work: for each view of the shadow atlas, its tile and, per
//! opaque mesh, the runs of triangles it draws, split into small and large clusters. On
//! a GPU the compute raster (`shadow_raster`) covers both, but for alpha MASK meshes'
//! clusters, which the hardware draws (`shadow_maps`); a CPU adapter's hardware draws
//! them all.
//! Made once per frame, output size, atlas and options by
//! [`GpuScene::shadow_work`](super::GpuScene::shadow_work), and shared by both passes.

use std::ops::Range;

use super::view_culling::{Fine, Runs};

/// Triangles in one compute item: one workgroup's, an invocation a triangle.
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

    /// The compute raster's items for the small clusters: per view, per small run,
    /// chunks of at most [`ITEM_TRIANGLES`] triangles as (view, instance, first index,
    /// triangles), in `shadow_compute.wgsl`'s `Item` layout.
    pub fn small_items(&self) -> Vec<[u32; 4]> {
        self.items(|mesh| &mesh.runs.small)
    }

    /// The compute raster's items for the large clusters the hardware does not draw:
    /// every large run but alpha MASK meshes', as [`small_items`](Self::small_items).
    pub fn large_items(&self) -> Vec<[u32; 4]> {
        const NONE: &[Range<u32>] = &[];
        self.items(|mesh| match mesh.masked {
            true => NONE,
            false => &mesh.runs.large,
        })
    }

    fn items(&self, runs: impl Fn(&MeshRuns) -> &[Range<u32>]) -> Vec<[u32; 4]> {
        let mut items = Vec::new();
        for (view, work) in (0u32..).zip(&self.views) {
            for mesh in &work.meshes {
                for run in runs(mesh) {
                    for start in (run.start..run.end).step_by(ITEM_TRIANGLES as usize) {
                        let count = (run.end - start).min(ITEM_TRIANGLES);
                        let first = mesh.indices(&(start..start + count)).start;
                        items.push([view, mesh.instance, first, count]);
                    }
                }
            }
        }
        items
    }
}

/// What makes a cluster small in a view of `side` texels, given the options.
pub(super) fn fine(options: &ShadowOptions, side: u32, masked: bool) -> Option<Fine> {
    let texels = options.small_texels.filter(|_| !masked && options.culled)?;
    Some(Fine {
        half_side: 0.5 * f64::from(side),
        texels,
    })
}
