//! What `render` and `bench` share: a pipeline loaded for a scene with the outputs a
//! command reads ([`Pipeline`]), a device ([`Session`]), and the pipeline compiled for
//! that device at one size, ready to run frames and read outputs back ([`Prepared`]).
//!
//! The order is the one that finds cheap mistakes before expensive work: the scene and
//! the pipeline load without a device, so a typo fails before an adapter is opened.

mod error;
mod pipeline;
mod prepared;
mod session;

pub use error::FrameError;
pub use pipeline::{host, Pipeline, Specialise};
pub use prepared::Prepared;
pub use session::Session;
