//! Tangents for normal maps, generated with MikkTSpace where a glTF primitive has none, as
//! the glTF spec asks (normal maps are baked against MikkTSpace tangents).

use super::mesh::Vertex;

/// Sets the tangent of every vertex `indices` (a triangle list) reaches from its position,
/// normal and texture coordinates of set `uv_set` (0: [`Vertex::uv`], 1: [`Vertex::uv1`]). MikkTSpace assumes OpenGL's texture coordinates (v up) while glTF's v
/// points down, so v is flipped on the way in: the bitangent then points along the normal
/// map's +Y (up in the image), which is what glTF's normal textures encode (three.js negates
/// the sign for glTF for the same reason). A vertex that several triangles share keeps the
/// last triangle's tangent; a vertex MikkTSpace gives none (degenerate surroundings) keeps
/// [`Vertex::NO_TANGENT`], so its normal is not perturbed. The UVs are taken as the vertices
/// hold them: a KHR_texture_transform rotation of the normal texture is not followed (its
/// tangent frame would have to turn with it). (bevy_mikktspace 1.0 has no error yet; it
/// reserves the right to add some.)
pub fn generate_tangents(
    vertices: &mut [Vertex],
    indices: &[u32],
    uv_set: u32,
) -> Result<(), bevy_mikktspace::GenerateTangentSpaceError> {
    bevy_mikktspace::generate_tangents(&mut Triangles {
        vertices,
        indices,
        uv_set,
    })
}

struct Triangles<'a> {
    vertices: &'a mut [Vertex],
    indices: &'a [u32],
    uv_set: u32,
}

impl Triangles<'_> {
    fn vertex(&self, face: usize, vert: usize) -> &Vertex {
        &self.vertices[self.indices[3 * face + vert] as usize]
    }
}

impl bevy_mikktspace::Geometry for Triangles<'_> {
    fn num_faces(&self) -> usize {
        self.indices.len() / 3
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.vertex(face, vert).position
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.vertex(face, vert).normal
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        let vertex = self.vertex(face, vert);
        let [u, v] = if self.uv_set == 1 {
            vertex.uv1
        } else {
            vertex.uv
        };
        [u, 1.0 - v]
    }

    fn set_tangent(
        &mut self,
        tangent_space: Option<bevy_mikktspace::TangentSpace>,
        face: usize,
        vert: usize,
    ) {
        if let Some(tangent_space) = tangent_space {
            let index = self.indices[3 * face + vert] as usize;
            self.vertices[index].tangent = Vertex::tangent_from(tangent_space.tangent_encoded());
        }
    }
}
