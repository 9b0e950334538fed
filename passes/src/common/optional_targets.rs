//! A pass whose file gives it optional textures (graph-core's optional writes and reads:
//! a G-buffer's material layers and pose offset, their readers), made for the set of them
//! each frame's plan keeps. Which of them a frame has is the plan's to say, and is known
//! only when recording, so a pass set up with them records through [`PerKept`], which
//! makes the pass for the set the plan keeps (composing its shader for it) the first time
//! a frame needs that set (common/gpu/per_kept.rs).

use rgraph_core::file::PluginError;
use rgraph_core::types::TextureFormat;
use rgraph_core::TextureHandle;

/// Optional textures of a pass, as its setup declared them, and which of them a frame's
/// plan keeps ([`Self::Set`]).
pub(crate) trait OptionalTargets: 'static {
    /// Which of them one frame keeps: what a pass is made for.
    type Set: Copy + Eq + 'static;

    /// Whether the file gives the pass none.
    fn is_empty(&self) -> bool;

    /// Every one of them: the most a pass set up with them meets, which its setup checks.
    fn all(&self) -> Self::Set;

    /// The set `has` keeps, each texture's format as `format` says.
    #[cfg_attr(not(feature = "gpu"), allow(dead_code))]
    fn kept(
        &self,
        has: &dyn Fn(TextureHandle) -> bool,
        format: &dyn Fn(TextureHandle) -> TextureFormat,
    ) -> Self::Set;

    /// Whether `set` keeps `handle`, one of these textures or another: every texture that
    /// is not one of them is kept.
    fn keeps(&self, set: Self::Set, handle: TextureHandle) -> bool;

    /// For each of a pass's attachments `handles`, in order, whether `set` keeps it
    /// (`FilledTargets::only`'s flags).
    fn kept_attachments(&self, set: Self::Set, handles: &[TextureHandle]) -> Vec<bool> {
        handles.iter().map(|&h| self.keeps(set, h)).collect()
    }
}

/// One optional texture, if the file gives the pass its slot: kept or not.
impl OptionalTargets for Option<TextureHandle> {
    type Set = bool;

    fn is_empty(&self) -> bool {
        self.is_none()
    }

    fn all(&self) -> bool {
        self.is_some()
    }

    fn kept(
        &self,
        has: &dyn Fn(TextureHandle) -> bool,
        _: &dyn Fn(TextureHandle) -> TextureFormat,
    ) -> bool {
        self.is_some_and(has)
    }

    fn keeps(&self, set: bool, handle: TextureHandle) -> bool {
        set || *self != Some(handle)
    }
}

/// Two kinds of optional textures of one pass, each kept as its own kind says.
impl<A: OptionalTargets, B: OptionalTargets> OptionalTargets for (A, B) {
    type Set = (A::Set, B::Set);

    fn is_empty(&self) -> bool {
        self.0.is_empty() && self.1.is_empty()
    }

    fn all(&self) -> Self::Set {
        (self.0.all(), self.1.all())
    }

    fn kept(
        &self,
        has: &dyn Fn(TextureHandle) -> bool,
        format: &dyn Fn(TextureHandle) -> TextureFormat,
    ) -> Self::Set {
        (self.0.kept(has, format), self.1.kept(has, format))
    }

    fn keeps(&self, set: Self::Set, handle: TextureHandle) -> bool {
        self.0.keeps(set.0, handle) && self.1.keeps(set.1, handle)
    }
}

/// What makes a pass with optional textures `T` for one set of them.
pub(crate) type MakeKept<T, R> = Box<dyn Fn(<T as OptionalTargets>::Set) -> Result<R, PluginError>>;

/// A pass set up with the optional textures `targets`, made for the set of them each
/// frame's plan keeps (common/gpu/per_kept.rs records it): `make` composes the pass for a
/// set. Setup makes it once for all of them, so that what would fail fails there, naming
/// the pass.
#[cfg_attr(not(feature = "gpu"), allow(dead_code))]
pub(crate) struct PerKept<T: OptionalTargets, R> {
    pub targets: T,
    pub make: MakeKept<T, R>,
}

impl<T: OptionalTargets, R> PerKept<T, R> {
    pub fn new(targets: T, make: MakeKept<T, R>) -> Result<PerKept<T, R>, PluginError> {
        make(targets.all())?;
        Ok(PerKept { targets, make })
    }
}
