//! Compiling a graph into a [`Plan`], without a GPU.

use crate::error::GraphErrors;
use crate::graph::Graph;
use crate::plan::Plan;
use crate::profile::DeviceProfile;

/// What a compile is for: the output size relative textures resolve against, and the
/// device whose limits and formats the graph must fit.
#[derive(Clone, Debug)]
pub struct CompileOptions {
    pub output_size: (u32, u32),
    pub profile: DeviceProfile,
}

impl Default for CompileOptions {
    fn default() -> Self {
        Self {
            output_size: (1920, 1080),
            profile: DeviceProfile::webgpu(),
        }
    }
}

impl Graph {
    /// Compiles the graph for `options`. Returns every error found, each naming its pass
    /// and resource; a graph that compiles is one the executor can run on a device that
    /// matches the profile.
    pub fn compile(&self, options: &CompileOptions) -> Result<Plan, GraphErrors> {
        let _ = options;
        todo!("compile phases")
    }
}
