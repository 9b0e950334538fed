//! Keyframe interpolation as glTF 2.0 defines it (§3.11 and Appendix C): STEP, LINEAR
//! (spherical for rotations) and CUBICSPLINE (Hermite, tangents scaled by the key
//! interval). Before the first key and after the last, the value is the nearest key's.

use std::ops::{Add, Mul};

use glam::DQuat;

use super::clip::Interpolation;

/// A value keyframes hold: vectors and quaternions, combined linearly.
pub(super) trait Value: Copy + Add<Output = Self> + Mul<f64, Output = Self> {
    /// The LINEAR interpolation between `a` and `b` at `s` in [0, 1].
    fn linear(a: Self, b: Self, s: f64) -> Self;
    /// What a cubic spline's blend of values becomes: itself, or a unit quaternion.
    fn finish_cubic(self) -> Self;
}

impl Value for f64 {
    fn linear(a: Self, b: Self, s: f64) -> Self {
        a + (b - a) * s
    }

    fn finish_cubic(self) -> Self {
        self
    }
}

impl Value for glam::DVec3 {
    fn linear(a: Self, b: Self, s: f64) -> Self {
        a.lerp(b, s)
    }

    fn finish_cubic(self) -> Self {
        self
    }
}

impl Value for DQuat {
    fn linear(a: Self, b: Self, s: f64) -> Self {
        slerp(a, b, s)
    }

    fn finish_cubic(self) -> Self {
        self.normalize()
    }
}

/// The value of the keyframes at `time`. `times` is non-empty and strictly increasing;
/// `values` holds one value per key, or three for CUBICSPLINE (in-tangent, value,
/// out-tangent), as the loader checked.
pub(super) fn sample<T: Value>(
    interpolation: Interpolation,
    times: &[f64],
    values: &[T],
    time: f64,
) -> T {
    let per_key = match interpolation {
        Interpolation::CubicSpline => 3,
        Interpolation::Step | Interpolation::Linear => 1,
    };
    // The key's value itself, past the in-tangent of a cubic spline's triple.
    let value = |k: usize| values[k * per_key + per_key / 2];
    let last = times.len() - 1;
    // The first key after `time`: 0 before the start, `times.len()` at or after the end.
    let next = times.partition_point(|&t| t <= time);
    if next == 0 {
        return value(0);
    }
    if next > last {
        return value(last);
    }
    let k = next - 1;
    let interval = times[next] - times[k];
    let s = (time - times[k]) / interval;
    match interpolation {
        Interpolation::Step => value(k),
        Interpolation::Linear => T::linear(value(k), value(next), s),
        Interpolation::CubicSpline => {
            let out_tangent = values[k * 3 + 2];
            let in_tangent = values[next * 3];
            let (s2, s3) = (s * s, s * s * s);
            let blended = value(k) * (2.0 * s3 - 3.0 * s2 + 1.0)
                + out_tangent * (interval * (s3 - 2.0 * s2 + s))
                + value(next) * (-2.0 * s3 + 3.0 * s2)
                + in_tangent * (interval * (s3 - s2));
            blended.finish_cubic()
        }
    }
}

/// Spherical linear interpolation from `a` to `b` along the shorter arc (`q` and `-q` are
/// one rotation: the nearer of the two is taken, as glTF's Appendix C says), falling back
/// to a normalised linear blend where the arc is too short for `sin` to divide by.
fn slerp(a: DQuat, b: DQuat, s: f64) -> DQuat {
    let dot = a.dot(b);
    let (b, dot) = if dot < 0.0 { (-b, -dot) } else { (b, dot) };
    if dot > 1.0 - 1e-9 {
        return (a * (1.0 - s) + b * s).normalize();
    }
    let angle = dot.acos();
    let sin = angle.sin();
    a * (((1.0 - s) * angle).sin() / sin) + b * ((s * angle).sin() / sin)
}
