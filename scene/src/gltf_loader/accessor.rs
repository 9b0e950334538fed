//! Bounds-checked accessor decoding.
//!
//! The `gltf` crate's own readers assume a well-formed file (they slice and assert), so a
//! truncated or inconsistent file could panic; this reader checks every offset and returns the
//! reason instead. It converts any component type to numbers as the glTF spec says, which also
//! covers KHR_mesh_quantization, and applies sparse substitution.

use gltf::accessor::{sparse::IndexType, DataType, Dimensions};

/// Most elements an accessor without a buffer view (all zeros plus sparse values) may have.
const MAX_VIEWLESS_ELEMENTS: usize = 1 << 24;

/// The bytes of a buffer view, or why they are not there.
pub(super) fn view_bytes<'b>(
    buffers: &'b [Vec<u8>],
    view: &gltf::buffer::View,
) -> Result<&'b [u8], String> {
    let buffer = view.buffer().index();
    let start = view.offset();
    let end = start.checked_add(view.length());
    buffers
        .get(buffer)
        .zip(end)
        .and_then(|(data, end)| data.get(start..end))
        .ok_or_else(|| {
            format!(
                "buffer view {} (bytes {start}..+{}) lies outside buffer {buffer}",
                view.index(),
                view.length()
            )
        })
}

/// Reads a `VECn`-typed accessor (n = `N`) as f32 vectors.
pub(super) fn read_vectors<const N: usize>(
    buffers: &[Vec<u8>],
    accessor: &gltf::Accessor,
) -> Result<Vec<[f32; N]>, String> {
    let dims = accessor.dimensions().multiplicity();
    if dims != N {
        return Err(format!("has {dims} components per element, expected {N}"));
    }
    let values = components(buffers, accessor)?;
    Ok(values
        .chunks_exact(N)
        .map(|c| std::array::from_fn(|i| c[i] as f32))
        .collect())
}

/// Reads an index accessor: scalar, unsigned integer components.
pub(super) fn read_indices(
    buffers: &[Vec<u8>],
    accessor: &gltf::Accessor,
) -> Result<Vec<u32>, String> {
    let integer = matches!(
        accessor.data_type(),
        DataType::U8 | DataType::U16 | DataType::U32
    );
    if accessor.dimensions().multiplicity() != 1 || !integer || accessor.normalized() {
        return Err("indices must be unnormalized UNSIGNED_BYTE/SHORT/INT scalars".to_owned());
    }
    // f64 holds every u32 exactly, so the round trip through `components` is lossless.
    Ok(components(buffers, accessor)?
        .into_iter()
        .map(|v| v as u32)
        .collect())
}

/// All components of all elements, `count * dims` values, element-major.
fn components(buffers: &[Vec<u8>], accessor: &gltf::Accessor) -> Result<Vec<f64>, String> {
    let dims = accessor.dimensions().multiplicity();
    let layout = Layout {
        component: accessor.data_type(),
        dims,
        normalized: accessor.normalized(),
    };
    let mut values = match accessor.view() {
        Some(view) => {
            let stride = view.stride().unwrap_or(layout.element_size());
            layout.read(
                view_bytes(buffers, &view)?,
                accessor.offset(),
                stride,
                accessor.count(),
            )?
        }
        // glTF: an accessor without a buffer view is all zeros (before sparse substitution).
        // No bytes back its count, so it is capped: a tiny file must not be able to ask for an
        // arbitrarily large allocation.
        None if accessor.count() > MAX_VIEWLESS_ELEMENTS => {
            return Err(format!(
                "{} elements without a buffer view (at most {MAX_VIEWLESS_ELEMENTS})",
                accessor.count()
            ))
        }
        None => vec![0.0; accessor.count() * dims],
    };
    if let Some(sparse) = accessor.sparse() {
        let count = sparse.count();
        let indices = sparse.indices();
        let index_layout = Layout {
            component: match indices.index_type() {
                IndexType::U8 => DataType::U8,
                IndexType::U16 => DataType::U16,
                IndexType::U32 => DataType::U32,
            },
            dims: 1,
            normalized: false,
        };
        let targets = index_layout.read(
            view_bytes(buffers, &indices.view())?,
            indices.offset(),
            index_layout.element_size(),
            count,
        )?;
        let values_view = sparse.values();
        let replacements = layout.read(
            view_bytes(buffers, &values_view.view())?,
            values_view.offset(),
            layout.element_size(),
            count,
        )?;
        for (target, replacement) in targets.into_iter().zip(replacements.chunks_exact(dims)) {
            let start = target as usize * dims;
            values
                .get_mut(start..start + dims)
                .ok_or_else(|| {
                    format!(
                        "sparse index {target} is past the accessor's {} elements",
                        accessor.count()
                    )
                })?
                .copy_from_slice(replacement);
        }
    }
    Ok(values)
}

/// How one element is encoded.
struct Layout {
    component: DataType,
    dims: usize,
    normalized: bool,
}

impl Layout {
    fn element_size(&self) -> usize {
        self.component.size() * self.dims
    }

    /// Decodes `count` elements starting at `offset`, `stride` bytes apart.
    fn read(
        &self,
        data: &[u8],
        offset: usize,
        stride: usize,
        count: usize,
    ) -> Result<Vec<f64>, String> {
        let size = self.component.size();
        if stride < self.element_size() {
            return Err(format!(
                "byte stride {stride} is smaller than the element size {}",
                self.element_size()
            ));
        }
        let end = offset
            .checked_add(self.element_size())
            .and_then(|first_end| match count {
                0 => Some(offset),
                _ => (count - 1).checked_mul(stride)?.checked_add(first_end),
            });
        if end.is_none_or(|end| end > data.len()) {
            return Err(format!(
                "{count} elements from byte {offset} with stride {stride} overrun its {} byte buffer view",
                data.len()
            ));
        }
        Ok((0..count)
            .flat_map(|i| (0..self.dims).map(move |c| offset + i * stride + c * size))
            .map(|at| self.decode(&data[at..at + size]))
            .collect())
    }

    /// One component; normalized integers map to [0, 1] (unsigned) or [-1, 1] (signed) as the
    /// glTF spec's `max(c / MAX, -1)` says.
    fn decode(&self, bytes: &[u8]) -> f64 {
        let (value, max) = match self.component {
            DataType::I8 => (f64::from(i8::from_le_bytes([bytes[0]])), f64::from(i8::MAX)),
            DataType::U8 => (f64::from(bytes[0]), f64::from(u8::MAX)),
            DataType::I16 => (
                f64::from(i16::from_le_bytes([bytes[0], bytes[1]])),
                f64::from(i16::MAX),
            ),
            DataType::U16 => (
                f64::from(u16::from_le_bytes([bytes[0], bytes[1]])),
                f64::from(u16::MAX),
            ),
            DataType::U32 => (
                f64::from(u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]])),
                f64::from(u32::MAX),
            ),
            DataType::F32 => {
                return f64::from(f32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]))
            }
        };
        if self.normalized {
            (value / max).max(-1.0)
        } else {
            value
        }
    }
}

/// An accessor type as glTF spells it.
pub(super) fn type_name(dimensions: Dimensions) -> &'static str {
    match dimensions {
        Dimensions::Scalar => "SCALAR",
        Dimensions::Vec2 => "VEC2",
        Dimensions::Vec3 => "VEC3",
        Dimensions::Vec4 => "VEC4",
        Dimensions::Mat2 => "MAT2",
        Dimensions::Mat3 => "MAT3",
        Dimensions::Mat4 => "MAT4",
    }
}

/// A component type as glTF spells it, "normalized " before it when it is.
pub(super) fn component_name(data_type: DataType, normalized: bool) -> String {
    let name = match data_type {
        DataType::I8 => "BYTE",
        DataType::U8 => "UNSIGNED_BYTE",
        DataType::I16 => "SHORT",
        DataType::U16 => "UNSIGNED_SHORT",
        DataType::U32 => "UNSIGNED_INT",
        DataType::F32 => "FLOAT",
    };
    match normalized {
        true => format!("normalized {name}"),
        false => name.to_owned(),
    }
}
