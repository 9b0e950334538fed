//! WGSL validation and binding reflection with naga.
