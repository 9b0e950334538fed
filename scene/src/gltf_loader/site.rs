//! Where in the file a primitive is, and the errors that name it.

use crate::SceneError;

/// Where in the file a primitive is, for error messages.
pub(super) struct Site<'a> {
    pub file: &'a std::path::Path,
    pub mesh: String,
    pub primitive: usize,
}

impl Site<'_> {
    pub fn invalid(&self, reason: String) -> SceneError {
        SceneError::InvalidPrimitive {
            file: self.file.to_owned(),
            mesh: self.mesh.clone(),
            primitive: self.primitive,
            reason,
        }
    }

    pub fn morph_error(
        &self,
        target: usize,
        attribute: &'static str,
        accessor: &gltf::Accessor,
        reason: String,
    ) -> SceneError {
        SceneError::InvalidMorphTarget {
            file: self.file.to_owned(),
            mesh: self.mesh.clone(),
            primitive: self.primitive,
            target,
            attribute,
            accessor: accessor.index(),
            reason,
        }
    }

    pub fn accessor_error(
        &self,
        attribute: &'static str,
        accessor: &gltf::Accessor,
        reason: String,
    ) -> SceneError {
        SceneError::InvalidAccessor {
            file: self.file.to_owned(),
            mesh: self.mesh.clone(),
            primitive: self.primitive,
            attribute,
            accessor: accessor.index(),
            reason,
        }
    }
}
