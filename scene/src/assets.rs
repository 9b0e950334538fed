//! What a glTF file may read besides itself: the folder its URIs may reach, and how large a
//! file may be.

use std::path::PathBuf;

/// The largest file a scene reads (the glTF file itself, each buffer, each image) unless
/// [`AssetPolicy::max_bytes`] says otherwise: 1 GiB, four times the largest model in the
/// glTF sample set with room for scanned assets.
pub const DEFAULT_MAX_ASSET_BYTES: u64 = 1 << 30;

/// The most memory a glTF scene may hold (vertices, indices, decoded textures with their
/// mips) unless [`AssetPolicy::max_scene_bytes`] says otherwise: 4 GiB. Each node that
/// places a mesh gets its own copy of the mesh's vertices, and each image is decoded on its
/// own (a few kilobytes of PNG can hold 400 MB of pixels), so a small file would otherwise
/// be able to ask for any amount of memory.
pub const DEFAULT_MAX_SCENE_BYTES: u64 = 4 << 30;

/// Where a glTF file's URIs may point, and the size cap on every file a scene reads.
///
/// By default a URI must stay inside the folder of the glTF file that names it: an absolute
/// path, a `../` that climbs out, or a symbolic link that leads out is an error naming the
/// URI, so a downloaded asset cannot read other files on the machine. `root` widens that to
/// everything under one more folder (the CLI's `--asset-root`). Data URIs and the GLB binary
/// chunk need no file. Only regular files are read (never FIFOs or devices).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AssetPolicy {
    /// A folder whose files URIs may also name, besides the glTF file's own folder.
    pub root: Option<PathBuf>,
    /// The largest file read, in bytes.
    pub max_bytes: u64,
    /// The most bytes of vertices, indices and decoded textures the scene may hold, over
    /// every placement of every mesh and every image; checked before each is built.
    pub max_scene_bytes: u64,
}

impl Default for AssetPolicy {
    fn default() -> Self {
        AssetPolicy {
            root: None,
            max_bytes: DEFAULT_MAX_ASSET_BYTES,
            max_scene_bytes: DEFAULT_MAX_SCENE_BYTES,
        }
    }
}
