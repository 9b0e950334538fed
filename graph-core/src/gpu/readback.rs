//! Copying textures and buffers back to the CPU, for tests, screenshots and tools. Each
//! call submits its own copy and blocks until the GPU has finished it. What a readback
//! returns is reserved before it is filled: a host that cannot hold it (a large
//! `--width`/`--height`, little memory left) is an error naming the bytes, not an abort.

use wgpu::{BufferUsages, TextureFormat, TextureUsages};

/// Why a readback failed.
#[derive(Debug, thiserror::Error)]
pub enum ReadbackError {
    /// The texture is multisampled: copies need one sample per texel.
    #[error(
        "the texture is {samples}x multisampled and cannot be copied; resolve it first \
         (resolve_output) or read its samples in a pass"
    )]
    Multisampled {
        /// Its sample count.
        samples: u32,
    },

    /// The texture or buffer was made without `COPY_SRC`.
    #[error(
        "the {what} lacks the COPY_SRC usage; export it from the graph (or create it with \
         COPY_SRC)"
    )]
    NotCopySource {
        /// "texture" or "buffer".
        what: &'static str,
    },

    /// The format has no single copyable layout (a combined depth-stencil format).
    #[error("the texture's format {format:?} has no single copyable layout")]
    UncopyableFormat {
        /// The texture's format.
        format: TextureFormat,
    },

    /// A typed readback of a texture of another format.
    #[error("the texture's format is {found:?}, expected {expected}")]
    WrongFormat {
        /// The formats the readback takes.
        expected: &'static str,
        /// The texture's format.
        found: TextureFormat,
    },

    /// A buffer whose size is not a multiple of 4 bytes.
    #[error("the buffer's size {size} is not a multiple of 4, which copies need")]
    UnalignedBuffer {
        /// Its size in bytes.
        size: u64,
    },

    /// Mapping the staging buffer failed (wgpu's message).
    #[error("mapping the readback buffer failed: {0}")]
    Map(String),

    /// Waiting for the copy to finish failed (a lost device, say).
    #[error("waiting for the GPU failed: {0}")]
    Poll(#[from] wgpu::PollError),

    /// The host cannot allocate the bytes the readback returns.
    #[error(
        "cannot allocate {bytes} bytes ({:.1} MiB) of host memory for {what}",
        *bytes as f64 / 1048576.0
    )]
    HostMemory {
        /// The bytes asked for.
        bytes: u64,
        /// What they were for.
        what: &'static str,
    },
}

/// An empty vector with room for `len` items, or [`ReadbackError::HostMemory`] naming the
/// bytes and `what` they were for.
pub(crate) fn reserve<T>(len: usize, what: &'static str) -> Result<Vec<T>, ReadbackError> {
    let mut vec = Vec::new();
    vec.try_reserve_exact(len)
        .map_err(|_| ReadbackError::HostMemory {
            bytes: (len as u64).saturating_mul(std::mem::size_of::<T>() as u64),
            what,
        })?;
    Ok(vec)
}

/// The bytes of mip 0, layer 0 of a single-sampled texture, rows tightly packed (no
/// 256-byte row padding), top row first. The texture needs `COPY_SRC`.
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<u8>, ReadbackError> {
    read_rows(device, queue, texture, 1, |row, bytes| {
        bytes.extend_from_slice(row)
    })
}

/// Mip 0, layer 0 of a single-sampled texture as `T`s of `texel_bytes` bytes each (rows
/// top first), each row's bytes appended by `append`; the vector is reserved before the
/// copy is mapped.
fn read_rows<T>(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    texel_bytes: usize,
    mut append: impl FnMut(&[u8], &mut Vec<T>),
) -> Result<Vec<T>, ReadbackError> {
    if texture.sample_count() > 1 {
        return Err(ReadbackError::Multisampled {
            samples: texture.sample_count(),
        });
    }
    if !texture.usage().contains(TextureUsages::COPY_SRC) {
        return Err(ReadbackError::NotCopySource { what: "texture" });
    }
    let format = texture.format();
    // Combined depth-stencil formats copy one aspect at a time, and some not at all.
    let Some(block) = format
        .block_copy_size(None)
        .filter(|_| format.block_dimensions() == (1, 1))
    else {
        return Err(ReadbackError::UncopyableFormat { format });
    };
    let (width, height) = (texture.width(), texture.height());
    let row = width as usize * block as usize;
    let padded = (width * block).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
        * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let count = row / texel_bytes * height as usize;
    let mut texels = reserve(count, "the texels read back")?;
    let staging = staging_buffer(device, u64::from(padded) * u64::from(height));
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("rgraph readback"),
    });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &staging,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    queue.submit([encoder.finish()]);
    with_mapped(device, &staging, |bytes| {
        for padded_row in bytes.chunks_exact(padded as usize) {
            append(&padded_row[..row], &mut texels);
        }
    })?;
    Ok(texels)
}

/// The whole contents of a buffer. The buffer needs `COPY_SRC` and a size that is a
/// multiple of 4.
pub fn read_buffer(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    buffer: &wgpu::Buffer,
) -> Result<Vec<u8>, ReadbackError> {
    if !buffer.usage().contains(BufferUsages::COPY_SRC) {
        return Err(ReadbackError::NotCopySource { what: "buffer" });
    }
    let size = buffer.size();
    if size.next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT) != size {
        return Err(ReadbackError::UnalignedBuffer { size });
    }
    let staging = staging_buffer(device, size);
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("rgraph readback"),
    });
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, Some(size));
    queue.submit([encoder.finish()]);
    map_read(device, &staging, "the buffer read back")
}

/// The texels of an `Rgba8Unorm` or `Rgba8UnormSrgb` texture, row by row (raw bytes: no
/// sRGB decoding).
pub fn read_rgba8(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<[u8; 4]>, ReadbackError> {
    expect_format(
        texture,
        &[TextureFormat::Rgba8Unorm, TextureFormat::Rgba8UnormSrgb],
        "Rgba8Unorm",
    )?;
    read_rows(device, queue, texture, 4, |row, texels| {
        texels.extend(row.chunks_exact(4).map(|t| [t[0], t[1], t[2], t[3]]));
    })
}

/// The texels of an `Rgba16Float` texture, row by row, widened to `f32`.
pub fn read_rgba16f(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<[f32; 4]>, ReadbackError> {
    expect_format(texture, &[TextureFormat::Rgba16Float], "Rgba16Float")?;
    read_rows(device, queue, texture, 8, |row, texels| {
        texels.extend(row.chunks_exact(8).map(|t| {
            let h = |i: usize| f16_to_f32(u16::from_le_bytes([t[2 * i], t[2 * i + 1]]));
            [h(0), h(1), h(2), h(3)]
        }));
    })
}

fn expect_format(
    texture: &wgpu::Texture,
    allowed: &[TextureFormat],
    expected: &'static str,
) -> Result<(), ReadbackError> {
    if allowed.contains(&texture.format()) {
        Ok(())
    } else {
        Err(ReadbackError::WrongFormat {
            expected,
            found: texture.format(),
        })
    }
}

/// IEEE 754 half to single precision, subnormals, infinities and NaN included.
fn f16_to_f32(bits: u16) -> f32 {
    let sign = if bits & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exponent = (bits >> 10) & 0x1f;
    let mantissa = (bits & 0x3ff) as f32;
    sign * match exponent {
        0 => mantissa * 2f32.powi(-24),
        0x1f if mantissa == 0.0 => f32::INFINITY,
        0x1f => f32::NAN,
        e => (1.0 + mantissa / 1024.0) * 2f32.powi(e as i32 - 15),
    }
}

fn staging_buffer(device: &wgpu::Device, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("rgraph readback staging"),
        size,
        usage: BufferUsages::MAP_READ | BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// Maps a `MAP_READ` buffer after the work already submitted, waits, and copies it out
/// into a vector reserved first (`what` names it in the error when the host cannot).
pub(crate) fn map_read(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    what: &'static str,
) -> Result<Vec<u8>, ReadbackError> {
    let mut bytes = reserve(buffer.size() as usize, what)?;
    with_mapped(device, buffer, |mapped| bytes.extend_from_slice(mapped))?;
    Ok(bytes)
}

/// Maps a `MAP_READ` buffer after the work already submitted, waits, hands its bytes to
/// `read` and unmaps it.
fn with_mapped<R>(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    read: impl FnOnce(&[u8]) -> R,
) -> Result<R, ReadbackError> {
    let (sender, receiver) = std::sync::mpsc::channel();
    buffer.map_async(wgpu::MapMode::Read, .., move |result| {
        // The receiver outlives the wait below; a failed send cannot happen.
        let _ = sender.send(result);
    });
    device.poll(wgpu::PollType::wait_indefinitely())?;
    match receiver.try_recv() {
        Ok(Ok(())) => {}
        Ok(Err(e)) => return Err(ReadbackError::Map(e.to_string())),
        Err(_) => return Err(ReadbackError::Map("the map callback never ran".into())),
    }
    let mapped = buffer
        .get_mapped_range(..)
        .map_err(|e| ReadbackError::Map(e.to_string()))?;
    let result = read(&mapped);
    drop(mapped);
    buffer.unmap();
    Ok(result)
}

#[cfg(test)]
mod tests {
    use super::{f16_to_f32, reserve, ReadbackError};

    #[test]
    fn a_host_that_cannot_hold_the_readback_is_an_error_naming_the_bytes() {
        // More than any address space: the reservation fails without touching memory.
        let huge = usize::MAX / 16;
        match reserve::<[f32; 4]>(huge, "the texels read back") {
            Err(e @ ReadbackError::HostMemory { .. }) => {
                let message = e.to_string();
                assert!(
                    message.starts_with(&format!(
                        "cannot allocate {} bytes",
                        (huge as u64).saturating_mul(16)
                    )),
                    "{message}"
                );
                assert!(message.ends_with("of host memory for the texels read back"));
            }
            other => panic!("expected HostMemory, got {:?}", other.map(|v| v.len())),
        }
        assert_eq!(reserve::<u8>(16, "x").map(|v| v.capacity()).ok(), Some(16));
    }

    #[test]
    fn halves_decode() {
        assert_eq!(f16_to_f32(0x3c00), 1.0);
        assert_eq!(f16_to_f32(0xc000), -2.0);
        assert_eq!(f16_to_f32(0x3800), 0.5);
        assert_eq!(f16_to_f32(0x0001), 2f32.powi(-24));
        assert_eq!(f16_to_f32(0x7c00), f32::INFINITY);
        assert!(f16_to_f32(0x7e00).is_nan());
    }
}
