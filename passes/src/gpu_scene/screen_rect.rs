//! Where camera-relative boxes may lie on screen: the rectangle of pixels covering them,
//! for a pass that needs to draw only there (keys_depth under the blended meshes).

use glam::{DMat4, DVec2, DVec3};

use rgraph_scene::{Aabb, Camera, DepthConvention};

/// A rectangle of pixels: columns `x..x + width`, rows `y..y + height`, neither empty.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelRect {
    /// First column.
    pub x: u32,
    /// First row (rows count down from the top).
    pub y: u32,
    /// Columns, at least 1.
    pub width: u32,
    /// Rows, at least 1.
    pub height: u32,
}

impl PixelRect {
    /// Every pixel of an output of `size`.
    pub fn full(size: (u32, u32)) -> PixelRect {
        PixelRect {
            x: 0,
            y: 0,
            width: size.0,
            height: size.1,
        }
    }
}

/// The pixels of an output of `size` that `boxes` (camera-relative) may cover, seen by
/// `camera`, with a pixel of margin for rounding: `None` where no box is in view, the
/// whole output where one reaches the camera's plane or behind it (its projection is
/// unbounded there). A box wholly in front projects inside the hull of its corners'
/// projections, so their bounds hold it.
pub fn screen_rect<'a>(
    camera: &Camera,
    size: (u32, u32),
    boxes: impl IntoIterator<Item = &'a Aabb>,
) -> Option<PixelRect> {
    let extent = DVec2::new(f64::from(size.0), f64::from(size.1));
    let aspect = size.0.max(1) as f32 / size.1.max(1) as f32;
    // x and y of clip space do not depend on the depth convention.
    let clip_from_view = camera
        .projection_matrix(aspect, DepthConvention::Standard)
        .as_dmat4();
    let clip_from_relative = clip_from_view * DMat4::from_quat(camera.orientation.inverse());
    let (mut low, mut high) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for bounds in boxes {
        for corner in 0..8 {
            let pick = |bit: u32, min: f64, max: f64| if corner & bit == 0 { min } else { max };
            let point = DVec3::new(
                pick(1, bounds.min.x, bounds.max.x),
                pick(2, bounds.min.y, bounds.max.y),
                pick(4, bounds.min.z, bounds.max.z),
            );
            let clip = clip_from_relative * point.extend(1.0);
            if clip.w <= 0.0 {
                return Some(PixelRect::full(size));
            }
            let ndc = clip.truncate().truncate() / clip.w;
            let pixel = DVec2::new(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * extent;
            low = low.min(pixel);
            high = high.max(pixel);
        }
    }
    let low = (low - 1.0).floor().max(DVec2::ZERO).min(extent);
    let high = (high + 1.0).ceil().max(DVec2::ZERO).min(extent);
    (low.x < high.x && low.y < high.y).then_some(PixelRect {
        x: low.x as u32,
        y: low.y as u32,
        width: (high.x - low.x) as u32,
        height: (high.y - low.y) as u32,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;
    use rgraph_scene::Projection;

    /// Looking down -Z from the origin, 90° vertically: a point at depth d and height h
    /// lies h / d of the half height above the centre.
    fn camera() -> Camera {
        Camera {
            name: "test".into(),
            position: DVec3::ZERO,
            orientation: DQuat::IDENTITY,
            projection: Projection::Perspective {
                yfov: std::f32::consts::FRAC_PI_2,
                znear: 0.1,
                zfar: None,
            },
        }
    }

    fn cube(center: DVec3, half: f64) -> Aabb {
        Aabb {
            min: center - half,
            max: center + half,
        }
    }

    #[test]
    fn a_box_in_front_covers_its_projection_and_a_pixel_more() {
        // The near face at depth 9 spans ±1/9 of the half size: 100 ± 11.1 pixels.
        let rect = screen_rect(
            &camera(),
            (200, 200),
            [&cube(DVec3::new(0.0, 0.0, -10.0), 1.0)],
        );
        assert_eq!(
            rect,
            Some(PixelRect {
                x: 87,
                y: 87,
                width: 26,
                height: 26
            })
        );
    }

    #[test]
    fn boxes_add_up_and_stop_at_the_output() {
        let left = cube(DVec3::new(-5.0, 0.0, -10.0), 1.0);
        let right = cube(DVec3::new(4.0, 3.0, -10.0), 0.5);
        let rect = screen_rect(&camera(), (200, 200), [&left, &right]).unwrap();
        // The left box's near face reaches x = (1 - 6/9) * 100 = 33.3; the right box's
        // far x = (1 + 4.5/9.5) * 100 and top y = (1 - 3.5/9.5) * 100.
        assert_eq!((rect.x, rect.y), (32, 62));
        assert_eq!((rect.x + rect.width, rect.y + rect.height), (149, 113));
        let wide = cube(DVec3::new(0.0, 0.0, -2.0), 1.5);
        assert_eq!(
            screen_rect(&camera(), (200, 100), [&wide]),
            Some(PixelRect::full((200, 100)))
        );
    }

    #[test]
    fn a_box_across_the_camera_plane_takes_the_whole_output() {
        let around = cube(DVec3::new(0.0, 0.0, 0.5), 1.0);
        assert_eq!(
            screen_rect(&camera(), (64, 48), [&around]),
            Some(PixelRect::full((64, 48)))
        );
    }

    #[test]
    fn nothing_in_view_is_no_rectangle() {
        let aside = cube(DVec3::new(30.0, 0.0, -10.0), 1.0);
        assert_eq!(screen_rect(&camera(), (64, 48), [&aside]), None);
        assert_eq!(screen_rect(&camera(), (64, 48), []), None);
    }
}
