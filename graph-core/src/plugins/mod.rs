//! Built-in generic plugins: clear, copy, blit, full-screen WGSL, compute WGSL.
