// The vertex layout every skinning vertex shader reads (attribute = binding): 0 position (3 floats), 1 normal
// (3 floats), 2 joints (4 x uint16, integer attribute), 3 weights (4 floats); shared by the transform
// feedback path (skinning.cpp) and the draw path (draw.cpp) so that the shaders see one layout.
#pragma once

#include <cstdint>

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

namespace cga::gpu::detail {

inline void bind_skin_streams(GLuint vao, GLuint positions, GLuint normals, GLuint joints, GLuint weights) {
  glVertexArrayVertexBuffer(vao, 0, positions, 0, 3 * sizeof(float));
  glVertexArrayVertexBuffer(vao, 1, normals, 0, 3 * sizeof(float));
  glVertexArrayVertexBuffer(vao, 2, joints, 0, 4 * sizeof(std::uint16_t));
  glVertexArrayVertexBuffer(vao, 3, weights, 0, 4 * sizeof(float));
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribFormat(vao, 1, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribIFormat(vao, 2, 4, GL_UNSIGNED_SHORT, 0);
  glVertexArrayAttribFormat(vao, 3, 4, GL_FLOAT, GL_FALSE, 0);
  for (GLuint a = 0; a < 4; ++a) {
    glVertexArrayAttribBinding(vao, a, a);
    glEnableVertexArrayAttrib(vao, a);
  }
}

}  // namespace cga::gpu::detail
