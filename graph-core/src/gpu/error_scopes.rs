//! Catching wgpu's validation and out-of-memory errors around a piece of work, so they
//! come back as values naming what failed instead of reaching the uncaptured handler.

/// Validation and out-of-memory scopes, pushed and popped together.
pub(crate) struct ErrorScopes {
    validation: wgpu::ErrorScopeGuard,
    out_of_memory: wgpu::ErrorScopeGuard,
}

impl ErrorScopes {
    pub fn push(device: &wgpu::Device) -> Self {
        let out_of_memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
        Self {
            validation,
            out_of_memory,
        }
    }

    /// The errors caught, one per line, if any. Native futures are ready at once.
    pub fn pop(self) -> Option<String> {
        let errors: Vec<String> = [
            pollster::block_on(self.validation.pop()),
            pollster::block_on(self.out_of_memory.pop()),
        ]
        .into_iter()
        .flatten()
        .map(|e| e.to_string())
        .collect();
        (!errors.is_empty()).then(|| errors.join("\n"))
    }
}
