//! The exact coverage of `builtin:unlit` at 4x MSAA, computed on the CPU from the scene's
//! own triangles: which surface every sample sees, at the standard sample positions.
//!
//! The scene's camera is orthographic with `xmag = ymag = 1` looking down -Z, so at N x N
//! world (x, y) is pixel `((x + 1) / 2 * N, (1 - y) / 2 * N)` and nearer means larger z.

use rgraph_scene::Scene;

use super::Image;

/// The 4x sample positions within a pixel (y down): Vulkan's standardSampleLocations,
/// which are D3D's. wgpu cannot query them, but every Vulkan driver that reports
/// `standardSampleLocations` (lavapipe does) must use these.
pub const SAMPLES_4X: [(f64, f64); 4] = [
    (0.375, 0.125),
    (0.875, 0.375),
    (0.125, 0.625),
    (0.625, 0.875),
];

/// Samples closer than this (in pixels) to a triangle edge, or with two surfaces closer
/// than this in depth, could go either way under the rasterizer's fixed-point snapping
/// (lavapipe: 8 subpixel bits, 1/256 pixel), so their pixels are not judged.
const AMBIGUOUS_PX: f64 = 1.0 / 64.0;
const AMBIGUOUS_DEPTH: f64 = 1e-4;

/// What one sample sees.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Hit {
    /// The mesh (one per shape), or `None` for the background.
    pub mesh: Option<usize>,
    /// The triangle within the mesh, as its first index's position.
    pub triangle: usize,
}

/// How an edge mask agrees with the model, over the pixels the model can call.
pub struct Judged {
    /// Pixels the mask marks.
    pub marked: usize,
    /// Pixels the model expects marked.
    pub expected: usize,
    /// One line per pixel where the two disagree.
    pub wrong: Vec<String>,
}

pub struct Coverage {
    pub n: u32,
    /// Per pixel (row-major), per sample.
    pub hits: Vec<[Hit; 4]>,
    /// Per pixel: whether some sample is too close to call.
    pub ambiguous: Vec<bool>,
    /// Per mesh: its linear RGB color.
    pub colors: Vec<[f64; 3]>,
    triangles: Vec<Triangle>,
}

/// A world position (x, y, z).
#[derive(Copy, Clone)]
struct P {
    x: f64,
    y: f64,
    z: f64,
}

struct Triangle {
    mesh: usize,
    first: usize,
    corners: [P; 3],
}

impl Coverage {
    pub fn of(scene: &Scene, n: u32) -> Coverage {
        let mut triangles = Vec::new();
        for (m, mesh) in scene.meshes.iter().enumerate() {
            let world: Vec<P> = mesh
                .world_positions()
                .map(|p| P {
                    x: p.x,
                    y: p.y,
                    z: p.z,
                })
                .collect();
            for (t, tri) in mesh.indices.chunks_exact(3).enumerate() {
                triangles.push(Triangle {
                    mesh: m,
                    first: 3 * t,
                    corners: [0, 1, 2].map(|i| world[tri[i] as usize]),
                });
            }
        }
        let colors = scene
            .meshes
            .iter()
            .map(|m| {
                let c = scene.materials[m.material].base_color_factor;
                [c[0], c[1], c[2]].map(f64::from)
            })
            .collect();
        let mut coverage = Coverage {
            n,
            hits: Vec::new(),
            ambiguous: Vec::new(),
            colors,
            triangles,
        };
        for y in 0..n {
            for x in 0..n {
                let mut ambiguous = false;
                let hits = SAMPLES_4X.map(|(dx, dy)| {
                    let (hit, unsure) = coverage.sample(f64::from(x) + dx, f64::from(y) + dy);
                    ambiguous |= unsure;
                    hit
                });
                coverage.hits.push(hits);
                coverage.ambiguous.push(ambiguous);
            }
        }
        coverage
    }

    /// The nearest triangle at pixel position (px, py), and whether that is uncertain.
    fn sample(&self, px: f64, py: f64) -> (Hit, bool) {
        let n = f64::from(self.n);
        let (x, y) = (px / n * 2.0 - 1.0, 1.0 - py / n * 2.0);
        let px_per_world = n / 2.0;
        let mut unsure = false;
        let mut best: Option<(f64, Hit)> = None;
        for t in &self.triangles {
            let [a, b, c] = t.corners;
            let edge = |p: P, q: P| {
                let e = (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x);
                let length = ((q.x - p.x).powi(2) + (q.y - p.y).powi(2)).sqrt();
                (e, e.abs() / length * px_per_world)
            };
            let [(e0, d0), (e1, d1), (e2, d2)] = [edge(a, b), edge(b, c), edge(c, a)];
            let inside =
                (e0 >= 0.0 && e1 >= 0.0 && e2 >= 0.0) || (e0 <= 0.0 && e1 <= 0.0 && e2 <= 0.0);
            unsure |= d0.min(d1).min(d2) < AMBIGUOUS_PX;
            if !inside {
                continue;
            }
            // Barycentric weights: each edge function weighs the opposite corner.
            let z = (e1 * a.z + e2 * b.z + e0 * c.z) / (e0 + e1 + e2);
            let hit = Hit {
                mesh: Some(t.mesh),
                triangle: t.first,
            };
            if let Some((best_z, best_hit)) = best {
                unsure |= best_hit.mesh != hit.mesh && (z - best_z).abs() < AMBIGUOUS_DEPTH;
            }
            if best.is_none_or(|(best_z, _)| z > best_z) {
                best = Some((z, hit));
            }
        }
        let hit = best.map_or(
            Hit {
                mesh: None,
                triangle: 0,
            },
            |(_, h)| h,
        );
        (hit, unsure)
    }

    fn index(&self, x: u32, y: u32) -> usize {
        (y * self.n + x) as usize
    }

    /// Each sample's linear color (black for the background), by pixel.
    pub fn sample_colors(&self) -> impl Fn(u32, u32) -> [[f64; 3]; 4] + '_ {
        move |x, y| {
            self.hits[self.index(x, y)].map(|hit| hit.mesh.map_or([0.0; 3], |m| self.colors[m]))
        }
    }

    /// The resolved linear color: the average of the samples' colors (black background).
    pub fn resolved(&self, x: u32, y: u32) -> [f64; 3] {
        let mut sum = [0.0; 3];
        for hit in &self.hits[self.index(x, y)] {
            if let Some(m) = hit.mesh {
                for (s, c) in sum.iter_mut().zip(self.colors[m]) {
                    *s += c;
                }
            }
        }
        sum.map(|s| s / 4.0)
    }

    /// Compares the pixels of `mark` in `mask` with the pixels where `expect` holds,
    /// skipping those too close to call.
    pub fn judge(
        &self,
        mask: &Image,
        mark: [u8; 4],
        expect: fn(&Self, u32, u32) -> bool,
    ) -> Judged {
        let mut judged = Judged {
            marked: 0,
            expected: 0,
            wrong: Vec::new(),
        };
        for y in 0..self.n {
            for x in 0..self.n {
                if self.is_ambiguous(x, y) {
                    continue;
                }
                let (is, should) = (mask.at(x, y) == mark, expect(self, x, y));
                judged.marked += usize::from(is);
                judged.expected += usize::from(should);
                if is != should {
                    judged
                        .wrong
                        .push(format!("({x}, {y}) marked {is}, expected {should}"));
                }
            }
        }
        judged
    }

    pub fn is_ambiguous(&self, x: u32, y: u32) -> bool {
        self.ambiguous[self.index(x, y)]
    }

    /// The samples see more than one surface (background counts as one).
    pub fn is_mixed(&self, x: u32, y: u32) -> bool {
        let hits = &self.hits[self.index(x, y)];
        hits.iter().any(|h| h.mesh != hits[0].mesh)
    }

    /// Some visible sample belongs to a triangle that covers only part of the pixel.
    pub fn is_partially_covered(&self, x: u32, y: u32) -> bool {
        let hits = &self.hits[self.index(x, y)];
        hits.iter()
            .any(|h| h.mesh.is_some() && !self.triangle_covers_pixel(x, y, h))
    }

    /// Whether `hit`'s triangle contains all four sample positions of the pixel (even
    /// those where another surface is in front).
    fn triangle_covers_pixel(&self, x: u32, y: u32, hit: &Hit) -> bool {
        let Some(t) = self
            .triangles
            .iter()
            .find(|t| Some(t.mesh) == hit.mesh && t.first == hit.triangle)
        else {
            return false;
        };
        let n = f64::from(self.n);
        SAMPLES_4X.iter().all(|(dx, dy)| {
            let (sx, sy) = (
                (f64::from(x) + dx) / n * 2.0 - 1.0,
                1.0 - (f64::from(y) + dy) / n * 2.0,
            );
            let [a, b, c] = t.corners;
            let e = |p: P, q: P| (q.x - p.x) * (sy - p.y) - (q.y - p.y) * (sx - p.x);
            let (e0, e1, e2) = (e(a, b), e(b, c), e(c, a));
            (e0 >= 0.0 && e1 >= 0.0 && e2 >= 0.0) || (e0 <= 0.0 && e1 <= 0.0 && e2 <= 0.0)
        })
    }

    /// How many pixels are ambiguous.
    pub fn ambiguous_count(&self) -> usize {
        self.ambiguous.iter().filter(|&&a| a).count()
    }
}
