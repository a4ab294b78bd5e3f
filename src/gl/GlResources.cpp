// The GL backend's meshes and textures: upload and release (the class: GlBackendImpl.h).
//
// Meshes: uploadMesh refuses (kNoHandle) attribute arrays that do not match the positions, index
// counts not a multiple of 3 (2 for segments, Mesh::topology), indices past the last vertex, and a
// triangleSource of the wrong length. Segments and points are drawn as GL_LINES and GL_POINTS, of
// GL's default width and size, 1. What a mesh may leave out (the software backend uses the same defaults): normals →
// (0,0,1), colours → white, uvs → (0,0), triangleSource → t for triangle t. id = firstId + source, added in the vertex
// stage in 32-bit unsigned arithmetic.
#include <cstdint>
#include <cstring>
#include <new>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "gl/GlApi.h"
#include "gl/GlBackendImpl.h"
#include "pipeline/IndexRanges.h"
#include "pipeline/Mipmaps.h"

namespace frugal::gl {

namespace {

GLint wrapMode(Wrap wrap) {
    switch (wrap) {
        case Wrap::Repeat:
            return GL_REPEAT;
        case Wrap::ClampToEdge:
            return GL_CLAMP_TO_EDGE;
        case Wrap::MirroredRepeat:
            return GL_MIRRORED_REPEAT;
    }
    return GL_REPEAT;
}

}  // namespace

MeshHandle GlBackend::uploadMesh(const Mesh& mesh) {
    // Bad data gets kNoHandle, never a GL call that reads out of bounds.
    if (!isUploadable(mesh)) return kNoHandle;
    const std::size_t vertices = mesh.positions.size();
    const std::size_t triangles = mesh.primitiveCount();

    activate();
    GlMesh m;
    m.triangles = std::uint32_t(triangles);
    m.mode = mesh.topology == Topology::Lines ? GL_LINES : mesh.topology == Topology::Points ? GL_POINTS : GL_TRIANGLES;
    m.corners = std::uint32_t(verticesPerPrimitive(mesh.topology));
    m.vertices = std::uint32_t(vertices);
    m.triangleSource = triangleSources(mesh);

    // One buffer, one section per attribute (positions, normals, colours, uvs, tangents).
    GLsizeiptr size = GLsizeiptr(vertices * sizeof(glm::vec3));
    const auto section = [&size](std::size_t count, std::size_t elementSize) -> GLintptr {
        if (count == 0) return -1;
        const GLintptr at = size;
        size += GLsizeiptr(count * elementSize);
        return at;
    };
    m.layout.normal = section(mesh.normals.size(), sizeof(glm::vec3));
    m.layout.color = section(mesh.colors.size(), sizeof(glm::vec4));
    m.layout.uv = section(mesh.uvs.size(), sizeof(glm::vec2));
    m.layout.tangent = section(mesh.tangents.size(), sizeof(glm::vec4));
    m.layout.size = size;
    std::vector<std::uint8_t> data(static_cast<std::size_t>(size));
    const auto put = [&data](GLintptr at, const void* source, std::size_t bytes) {
        if (at >= 0 && bytes > 0) std::memcpy(data.data() + at, source, bytes);
    };
    put(0, mesh.positions.data(), vertices * sizeof(glm::vec3));
    put(m.layout.normal, mesh.normals.data(), mesh.normals.size() * sizeof(glm::vec3));
    put(m.layout.color, mesh.colors.data(), mesh.colors.size() * sizeof(glm::vec4));
    put(m.layout.uv, mesh.uvs.data(), mesh.uvs.size() * sizeof(glm::vec2));
    put(m.layout.tangent, mesh.tangents.data(), mesh.tangents.size() * sizeof(glm::vec4));

    gl_.GenVertexArrays(1, &m.vao);
    gl_.GenBuffers(1, &m.vbo);
    gl_.GenBuffers(1, &m.ibo);
    state_.bindVao(m.vao);
    gl_.BindBuffer(GL_ARRAY_BUFFER, m.vbo);
    gl_.BufferData(GL_ARRAY_BUFFER, size, data.data(), GL_STATIC_DRAW);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ibo);
    gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                   mesh.indices.data(), GL_STATIC_DRAW);
    setVertexLayout(m.vao, m.vbo, m.ibo, m.layout);
    check("uploadMesh");
    return meshes_.add(std::move(m));
}

bool GlBackend::updateVertices(MeshHandle mesh, std::span<const glm::vec3> positions,
                               std::span<const glm::vec3> normals, std::span<const glm::vec4> tangents) {
    GlMesh* m = meshes_.find(mesh);
    if (m == nullptr || positions.size() != m->vertices ||
        (!normals.empty() && (m->layout.normal < 0 || normals.size() != m->vertices)) ||
        (!tangents.empty() && (m->layout.tangent < 0 || tangents.size() != m->vertices)))
        return false;
    activate();
    // In place: GL keeps what draws already submitted read (llvmpipe waits for them).
    const auto put = [this](GLuint buffer, GLintptr at, const void* data, std::size_t bytes) {
        if (bytes == 0) return;
        gl_.BindBuffer(GL_ARRAY_BUFFER, buffer);
        gl_.BufferSubData(GL_ARRAY_BUFFER, at, GLsizeiptr(bytes), data);
    };
    put(m->vbo, 0, positions.data(), positions.size_bytes());
    put(m->vbo, m->layout.normal, normals.data(), normals.size_bytes());
    put(m->vbo, m->layout.tangent, tangents.data(), tangents.size_bytes());
    if (m->idVbo != 0) {  // the id pass's expanded copy: the same values gathered by the indices
        if (m->indices.empty()) {
            m->indices.resize(std::size_t(m->triangles) * m->corners);
            readBuffer(m->ibo, m->indices.data(), GLsizeiptr(m->indices.size() * sizeof(std::uint32_t)));
        }
        const auto gather = [&](GLintptr at, const auto& values) {
            using Value = typename std::decay_t<decltype(values)>::value_type;
            if (values.empty()) return;
            std::vector<Value> expanded(m->indices.size());
            for (std::size_t k = 0; k < expanded.size(); ++k) expanded[k] = values[m->indices[k]];
            put(m->idVbo, at, expanded.data(), expanded.size() * sizeof(Value));
        };
        gather(0, positions);
        gather(m->idLayout.normal, normals);
        gather(m->idLayout.tangent, tangents);
    }
    check("updateVertices");
    return true;
}

void GlBackend::setVertexLayout(GLuint vao, GLuint vbo, GLuint ibo, const VertexLayout& layout) {
    state_.bindVao(vao);
    gl_.BindBuffer(GL_ARRAY_BUFFER, vbo);
    if (ibo) gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);  // VAO state
    const auto offset = [](GLintptr bytes) { return reinterpret_cast<const void*>(bytes); };
    gl_.EnableVertexAttribArray(kPosition);
    gl_.VertexAttribPointer(kPosition, 3, GL_FLOAT, GL_FALSE, 0, offset(0));
    if (layout.normal >= 0) {
        gl_.EnableVertexAttribArray(kNormal);
        gl_.VertexAttribPointer(kNormal, 3, GL_FLOAT, GL_FALSE, 0, offset(layout.normal));
    }
    if (layout.color >= 0) {
        gl_.EnableVertexAttribArray(kColor);
        gl_.VertexAttribPointer(kColor, 4, GL_FLOAT, GL_FALSE, 0, offset(layout.color));
    }
    if (layout.uv >= 0) {
        gl_.EnableVertexAttribArray(kUv);
        gl_.VertexAttribPointer(kUv, 2, GL_FLOAT, GL_FALSE, 0, offset(layout.uv));
    }
    if (layout.tangent >= 0) {
        gl_.EnableVertexAttribArray(kTangent);
        gl_.VertexAttribPointer(kTangent, 4, GL_FLOAT, GL_FALSE, 0, offset(layout.tangent));
    }
    if (layout.id >= 0) {
        gl_.EnableVertexAttribArray(kId);
        gl_.VertexAttribIPointer(kId, 1, GL_UNSIGNED_INT, 0, offset(layout.id));
    }
}

void GlBackend::releaseMesh(MeshHandle mesh) {
    GlMesh* m = meshes_.find(mesh);
    if (m == nullptr) return;
    activate();
    deleteMesh(*m);  // GL keeps the objects alive until draws already queued have used them
    meshes_.remove(mesh);
    check("releaseMesh");
}

void GlBackend::deleteMesh(GlMesh& m) {
    state_.forgetVao(m.vao);  // deleting a bound object binds 0 in its place (GlStateCache.h)
    if (m.idVao != 0) state_.forgetVao(m.idVao);
    gl_.DeleteVertexArrays(1, &m.vao);
    gl_.DeleteBuffers(1, &m.vbo);
    gl_.DeleteBuffers(1, &m.ibo);
    if (m.idVao) gl_.DeleteVertexArrays(1, &m.idVao);
    if (m.idVbo) gl_.DeleteBuffers(1, &m.idVbo);
}

TextureHandle GlBackend::uploadTexture(const Texture& texture) {
    if (texture.width <= 0 || texture.height <= 0 || texture.width > maxTextureSize_ ||
        texture.height > maxTextureSize_ ||
        texture.rgba.size() != std::size_t(texture.width) * std::size_t(texture.height) * 4)
        return kNoHandle;
    activate();
    GLuint name = 0;
    gl_.GenTextures(1, &name);
    state_.bindTexture(name);
    // Rows as stored: the first row is v = 0, which is where glTF puts (0,0) (frugal/Scene.h).
    // An sRGB texture is decoded to linear by the sampler, before filtering (GL 3.3, 3.8.15).
    const GLint format = texture.srgb ? GLint(GL_SRGB8_ALPHA8) : GLint(GL_RGBA8);
    gl_.TexImage2D(GL_TEXTURE_2D, 0, format, texture.width, texture.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                   texture.rgba.data());
    // Mipmaps made on the CPU (pipeline/Mipmaps.h), level by level: the software reference samples
    // the same texels, which glGenerateMipmap (each driver's own filter) would not promise.
    int levels = 1;
    if (texture.mipmaps != MipFilter::None) {
        std::vector<MipLevel> mips;
        try {
            mips = mipLevels(texture);
        } catch (const std::bad_alloc&) {
            gl_.DeleteTextures(1, &name);
            state_.forgetTexture(name);
            return kNoHandle;
        }
        for (const MipLevel& level : mips)
            gl_.TexImage2D(GL_TEXTURE_2D, levels++, format, level.width, level.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                           level.rgba.data());
    }
    const auto glFilter = [](Filter f) { return f == Filter::Nearest ? GL_NEAREST : GL_LINEAR; };
    GLint minFilter = glFilter(texture.minFilter);
    if (texture.mipmaps == MipFilter::Nearest)
        minFilter = texture.minFilter == Filter::Nearest ? GL_NEAREST_MIPMAP_NEAREST : GL_LINEAR_MIPMAP_NEAREST;
    else if (texture.mipmaps == MipFilter::Linear)
        minFilter = texture.minFilter == Filter::Nearest ? GL_NEAREST_MIPMAP_LINEAR : GL_LINEAR_MIPMAP_LINEAR;
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, minFilter);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, glFilter(texture.filter));
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrapMode(texture.wrapS));
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrapMode(texture.wrapT));
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels - 1);
    if (gl_.GetError() != GL_NO_ERROR) {
        gl_.DeleteTextures(1, &name);
        state_.forgetTexture(name);
        return kNoHandle;
    }
    return textures_.add(name);
}

void GlBackend::releaseTexture(TextureHandle texture) {
    GLuint* t = textures_.find(texture);
    if (t == nullptr) return;
    activate();
    state_.forgetTexture(*t);  // as in deleteMesh
    gl_.DeleteTextures(1, t);
    textures_.remove(texture);
    check("releaseTexture");
}

}  // namespace frugal::gl
