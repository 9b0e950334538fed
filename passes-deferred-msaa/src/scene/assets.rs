//! What a glTF file may read besides itself: the folder its URIs may reach, and how large a
//! file may be.

use std::path::PathBuf;

/// The largest file a scene reads (the glTF file itself, each buffer, each image) unless
/// [`AssetPolicy::max_bytes`] says otherwise: 1 GiB, four times the largest model in the
/// glTF sample set with room for scanned assets.
pub const DEFAULT_MAX_ASSET_BYTES: u64 = 1 << 30;

/// The most vertex and index bytes a glTF scene may build unless
/// [`AssetPolicy::max_geometry_bytes`] says otherwise: 4 GiB. Each node that places a mesh
/// gets its own copy of the mesh's vertices, so a small file placing one large mesh from
/// many nodes would otherwise ask for any amount of memory.
pub const DEFAULT_MAX_GEOMETRY_BYTES: u64 = 4 << 30;

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
    /// The most bytes of vertices and indices the scene may hold, over every placement of
    /// every mesh; checked before each primitive is decoded.
    pub max_geometry_bytes: u64,
}

impl Default for AssetPolicy {
    fn default() -> Self {
        AssetPolicy {
            root: None,
            max_bytes: DEFAULT_MAX_ASSET_BYTES,
            max_geometry_bytes: DEFAULT_MAX_GEOMETRY_BYTES,
        }
    }
}
