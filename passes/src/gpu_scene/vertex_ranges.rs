//! How the scene's vertex buffer is bound for the visibility passes: in up to
//! [`VERTEX_RANGES`] storage bindings of one buffer, each a window of whole vertices at an
//! offset the device allows, so that a scene may hold more vertex bytes than one storage
//! binding (`max_storage_buffer_binding_size`, 2 GiB on an H100: the 100M-triangle
//! terrain's 50M vertices take 2.8 GB). geometry.wgsl's `vertex_words` finds a vertex's
//! range from the first range's length, so every range but the last holds as many
//! vertices as the first.
//!
//! The index buffer stays one binding: 12 bytes a triangle, 178,956,970 triangles in 2 GiB.

use std::ops::Range;

use rgraph_scene::Vertex;

/// How many ranges geometry.wgsl binds the vertices through (`vertex_range_0` to
/// `vertex_range_3`, group 2's bindings 0, 2, 3 and 4).
pub(super) const VERTEX_RANGES: usize = 4;

const STRIDE: u64 = std::mem::size_of::<Vertex>() as u64;

/// The byte ranges of a vertex buffer of `vertex_bytes` that `limits`' device binds it
/// through, in order: one for a buffer one binding holds, else windows of the most whole
/// vertices a binding holds whose size is a multiple of the storage offset alignment, the
/// last holding the rest. An error naming the bytes and the limit when
/// [`VERTEX_RANGES`] ranges cannot hold them.
pub(super) fn vertex_ranges(
    vertex_bytes: u64,
    limits: &wgpu::Limits,
) -> Result<Vec<Range<u64>>, String> {
    let limit = limits.max_storage_buffer_binding_size;
    if vertex_bytes <= limit {
        return Ok(std::iter::once(0..vertex_bytes).collect());
    }
    let alignment = u64::from(limits.min_storage_buffer_offset_alignment);
    let step = STRIDE / gcd(STRIDE, alignment) * alignment;
    let window = limit / step * step;
    let needed = match window {
        0 => None,
        window => Some(vertex_bytes.div_ceil(window)),
    };
    match needed {
        Some(count) if count <= VERTEX_RANGES as u64 => Ok((0..count)
            .map(|k| k * window..((k + 1) * window).min(vertex_bytes))
            .collect()),
        _ => Err(format!(
            "the scene's vertices take {vertex_bytes} bytes, more than the \
             {VERTEX_RANGES} ranges of {window} bytes a visibility buffer binds them through \
             on this device (storage bindings of at most {limit} bytes, \
             max_storage_buffer_binding_size, at offsets that are multiples of {alignment} \
             bytes and of the {STRIDE}-byte vertex): use a G-buffer pipeline"
        )),
    }
}

fn gcd(a: u64, b: u64) -> u64 {
    match b {
        0 => a,
        b => gcd(b, a % b),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits(binding: u64, alignment: u32) -> wgpu::Limits {
        wgpu::Limits {
            max_storage_buffer_binding_size: binding,
            min_storage_buffer_offset_alignment: alignment,
            ..wgpu::Limits::default()
        }
    }

    /// geometry.wgsl declares one binding a range.
    #[test]
    fn the_shader_binds_every_range() {
        let shader = include_str!("../wgsl/geometry.wgsl");
        let declared = (0..8)
            .filter(|k| shader.contains(&format!("var<storage, read> vertex_range_{k}:")))
            .count();
        assert_eq!(declared, VERTEX_RANGES);
    }

    #[test]
    fn one_binding_holds_what_fits() {
        let ranges = vertex_ranges(1 << 20, &limits(1 << 20, 256)).unwrap();
        assert_eq!(ranges, std::iter::once(0..1 << 20).collect::<Vec<_>>());
    }

    /// The 100M-triangle terrain (`builtin:terrain?cells=7071`: 7072^2 vertices) on an
    /// H100 (bindings of 2^31 - 1 bytes, offsets of 16): two ranges, the first of
    /// 38,347,922 vertices.
    #[test]
    fn the_100m_terrain_takes_two_ranges_on_an_h100() {
        let bytes = 7072u64 * 7072 * STRIDE;
        assert_eq!(bytes, 2_800_738_304);
        let ranges = vertex_ranges(bytes, &limits((1 << 31) - 1, 16)).unwrap();
        assert_eq!(ranges, [0..2_147_483_632, 2_147_483_632..bytes]);
        assert_eq!(ranges[0].end % STRIDE, 0);
        assert_eq!(ranges[0].end / STRIDE, 38_347_922);
    }

    /// Offsets stay multiples of the alignment and of the vertex: 256 and 56 bytes give
    /// windows of a multiple of 32 vertices.
    #[test]
    fn windows_are_whole_vertices_at_aligned_offsets() {
        let ranges = vertex_ranges(1_000_000, &limits(300_000, 256)).unwrap();
        assert_eq!(ranges.len(), 4);
        for range in &ranges[..3] {
            assert_eq!(range.end - range.start, 299_264);
            assert_eq!(range.start % 256, 0);
            assert_eq!(range.start % STRIDE, 0);
        }
        assert_eq!(ranges[3], 897_792..1_000_000);
    }

    /// lavapipe (bindings of 128 MiB, offsets of 32): 4 ranges of 2,396,744 vertices.
    #[test]
    fn past_every_range_is_an_error_naming_bytes_and_limit() {
        let lavapipe = limits(128 << 20, 32);
        let most = 4 * 2_396_744 * STRIDE;
        assert_eq!(vertex_ranges(most, &lavapipe).unwrap().len(), 4);
        let error = vertex_ranges(most + STRIDE, &lavapipe).unwrap_err();
        assert!(
            error.contains(&format!("vertices take {} bytes", most + STRIDE))
                && error.contains("4 ranges of 134217664 bytes")
                && error.contains("at most 134217728 bytes, max_storage_buffer_binding_size"),
            "{error}"
        );
    }
}
