// The OpenGL 3.3 core entry points the renderer uses, as a table of function
// pointers filled from a context backend's get-proc-address. Nothing in TetLOD
// calls gl* symbols directly or links libGL/libOSMesa, so backends (OSMesa, GLFW,
// EGL surfaceless later) can be swapped without touching the renderer.
#pragma once

#include <GL/glcorearb.h>

#include <string>

namespace tetlod::render {

// Returns the address of a GL function by name, or null (the backend's
// get-proc-address: OSMesaGetProcAddress, glfwGetProcAddress, eglGetProcAddress).
using GetProcAddress = void* (*)(const char* name);

// X-macro list: (member name, PFN type suffix). The GL name is "gl" + member.
#define TETLOD_GL_FUNCTIONS(X)                                      \
  X(ActiveTexture, ACTIVETEXTURE)                                   \
  X(AttachShader, ATTACHSHADER)                                     \
  X(BindBuffer, BINDBUFFER)                                         \
  X(BindFramebuffer, BINDFRAMEBUFFER)                               \
  X(BindRenderbuffer, BINDRENDERBUFFER)                             \
  X(BindTexture, BINDTEXTURE)                                       \
  X(BindVertexArray, BINDVERTEXARRAY)                               \
  X(BlendFuncSeparate, BLENDFUNCSEPARATE)                           \
  X(BlitFramebuffer, BLITFRAMEBUFFER)                               \
  X(BufferData, BUFFERDATA)                                         \
  X(BufferSubData, BUFFERSUBDATA)                                   \
  X(CheckFramebufferStatus, CHECKFRAMEBUFFERSTATUS)                 \
  X(Clear, CLEAR)                                                   \
  X(ClearColor, CLEARCOLOR)                                         \
  X(CompileShader, COMPILESHADER)                                   \
  X(CreateProgram, CREATEPROGRAM)                                   \
  X(CreateShader, CREATESHADER)                                     \
  X(DeleteBuffers, DELETEBUFFERS)                                   \
  X(DeleteFramebuffers, DELETEFRAMEBUFFERS)                         \
  X(DeleteProgram, DELETEPROGRAM)                                   \
  X(DeleteRenderbuffers, DELETERENDERBUFFERS)                       \
  X(DeleteShader, DELETESHADER)                                     \
  X(DeleteTextures, DELETETEXTURES)                                 \
  X(DeleteVertexArrays, DELETEVERTEXARRAYS)                         \
  X(DepthFunc, DEPTHFUNC)                                           \
  X(DepthMask, DEPTHMASK)                                           \
  X(Disable, DISABLE)                                               \
  X(DrawArrays, DRAWARRAYS)                                         \
  X(Enable, ENABLE)                                                 \
  X(EnableVertexAttribArray, ENABLEVERTEXATTRIBARRAY)               \
  X(Finish, FINISH)                                                 \
  X(FramebufferRenderbuffer, FRAMEBUFFERRENDERBUFFER)               \
  X(GenBuffers, GENBUFFERS)                                         \
  X(GenFramebuffers, GENFRAMEBUFFERS)                               \
  X(GenRenderbuffers, GENRENDERBUFFERS)                             \
  X(GenTextures, GENTEXTURES)                                       \
  X(GenVertexArrays, GENVERTEXARRAYS)                               \
  X(GetError, GETERROR)                                             \
  X(GetIntegerv, GETINTEGERV)                                       \
  X(GetProgramInfoLog, GETPROGRAMINFOLOG)                           \
  X(GetProgramiv, GETPROGRAMIV)                                     \
  X(GetShaderInfoLog, GETSHADERINFOLOG)                             \
  X(GetShaderiv, GETSHADERIV)                                       \
  X(GetString, GETSTRING)                                           \
  X(GetUniformLocation, GETUNIFORMLOCATION)                         \
  X(LinkProgram, LINKPROGRAM)                                       \
  X(PixelStorei, PIXELSTOREI)                                       \
  X(ReadBuffer, READBUFFER)                                         \
  X(ReadPixels, READPIXELS)                                         \
  X(RenderbufferStorage, RENDERBUFFERSTORAGE)                       \
  X(RenderbufferStorageMultisample, RENDERBUFFERSTORAGEMULTISAMPLE) \
  X(ShaderSource, SHADERSOURCE)                                     \
  X(TexImage2D, TEXIMAGE2D)                                         \
  X(TexParameteri, TEXPARAMETERI)                                   \
  X(Uniform1f, UNIFORM1F)                                           \
  X(Uniform1i, UNIFORM1I)                                           \
  X(Uniform2f, UNIFORM2F)                                           \
  X(Uniform3f, UNIFORM3F)                                           \
  X(Uniform3fv, UNIFORM3FV)                                         \
  X(UniformMatrix4fv, UNIFORMMATRIX4FV)                             \
  X(UseProgram, USEPROGRAM)                                         \
  X(VertexAttribIPointer, VERTEXATTRIBIPOINTER)                     \
  X(VertexAttribPointer, VERTEXATTRIBPOINTER)                       \
  X(Viewport, VIEWPORT)

struct GlApi {
#define TETLOD_GL_MEMBER(name, type) PFNGL##type##PROC name = nullptr;
  TETLOD_GL_FUNCTIONS(TETLOD_GL_MEMBER)
#undef TETLOD_GL_MEMBER
};

// Fills `api` through `get_proc`. Returns false and names the first missing entry
// point in `error` if any is unavailable.
bool load_gl_api(GetProcAddress get_proc, GlApi* api, std::string* error);

}  // namespace tetlod::render
