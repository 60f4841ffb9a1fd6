// The OpenGL 4.5 core entry points photovr uses, loaded through the current context's
// own proc-address function. Linking libGL and libOSMesa together routes calls to glvnd
// with no current context (../shared/reference/platform.md), so nothing here is linked
// statically: every pointer lives in namespace photovr::gl::api, whose mangled names
// cannot collide with the GL libraries' exported symbols.
#pragma once

#include <GL/glcorearb.h>

#define PHOTOVR_GL_FUNCTIONS(X)                                          \
  X(PFNGLGETSTRINGPROC, GetString)                                       \
  X(PFNGLGETSTRINGIPROC, GetStringi)                                     \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                   \
  X(PFNGLGETERRORPROC, GetError)                                         \
  X(PFNGLENABLEPROC, Enable)                                             \
  X(PFNGLDISABLEPROC, Disable)                                           \
  X(PFNGLVIEWPORTPROC, Viewport)                                         \
  X(PFNGLVIEWPORTINDEXEDFPROC, ViewportIndexedf)                         \
  X(PFNGLCLIPCONTROLPROC, ClipControl)                                   \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                       \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                       \
  X(PFNGLCULLFACEPROC, CullFace)                                         \
  X(PFNGLFRONTFACEPROC, FrontFace)                                       \
  X(PFNGLFINISHPROC, Finish)                                             \
  X(PFNGLFLUSHPROC, Flush)                                               \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                   \
  X(PFNGLCREATETEXTURESPROC, CreateTextures)                             \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                             \
  X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                         \
  X(PFNGLTEXTURESTORAGE3DPROC, TextureStorage3D)                         \
  X(PFNGLTEXTURESUBIMAGE2DPROC, TextureSubImage2D)                       \
  X(PFNGLTEXTUREPARAMETERIPROC, TextureParameteri)                       \
  X(PFNGLTEXTUREPARAMETERFPROC, TextureParameterf)                       \
  X(PFNGLGENERATETEXTUREMIPMAPPROC, GenerateTextureMipmap)               \
  X(PFNGLBINDTEXTUREUNITPROC, BindTextureUnit)                           \
  X(PFNGLGETTEXTURESUBIMAGEPROC, GetTextureSubImage)                     \
  X(PFNGLCOPYIMAGESUBDATAPROC, CopyImageSubData)                         \
  X(PFNGLCREATEFRAMEBUFFERSPROC, CreateFramebuffers)                     \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                     \
  X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, NamedFramebufferTexture)           \
  X(PFNGLNAMEDFRAMEBUFFERTEXTURELAYERPROC, NamedFramebufferTextureLayer) \
  X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, NamedFramebufferDrawBuffers)   \
  X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, CheckNamedFramebufferStatus)   \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                           \
  X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, ClearNamedFramebufferfv)           \
  X(PFNGLCLEARNAMEDFRAMEBUFFERUIVPROC, ClearNamedFramebufferuiv)         \
  X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                               \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                               \
  X(PFNGLNAMEDBUFFERSTORAGEPROC, NamedBufferStorage)                     \
  X(PFNGLNAMEDBUFFERSUBDATAPROC, NamedBufferSubData)                     \
  X(PFNGLGETNAMEDBUFFERSUBDATAPROC, GetNamedBufferSubData)               \
  X(PFNGLCLEARNAMEDBUFFERDATAPROC, ClearNamedBufferData)                 \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                             \
  X(PFNGLBINDBUFFERRANGEPROC, BindBufferRange)                           \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                     \
  X(PFNGLMAPNAMEDBUFFERRANGEPROC, MapNamedBufferRange)                   \
  X(PFNGLUNMAPNAMEDBUFFERPROC, UnmapNamedBuffer)                         \
  X(PFNGLFENCESYNCPROC, FenceSync)                                       \
  X(PFNGLCLIENTWAITSYNCPROC, ClientWaitSync)                             \
  X(PFNGLDELETESYNCPROC, DeleteSync)                                     \
  X(PFNGLCREATEVERTEXARRAYSPROC, CreateVertexArrays)                     \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                     \
  X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, VertexArrayVertexBuffer)           \
  X(PFNGLVERTEXARRAYELEMENTBUFFERPROC, VertexArrayElementBuffer)         \
  X(PFNGLENABLEVERTEXARRAYATTRIBPROC, EnableVertexArrayAttrib)           \
  X(PFNGLVERTEXARRAYATTRIBFORMATPROC, VertexArrayAttribFormat)           \
  X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, VertexArrayAttribBinding)         \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                           \
  X(PFNGLDRAWELEMENTSINSTANCEDPROC, DrawElementsInstanced)               \
  X(PFNGLCREATESHADERPROC, CreateShader)                                 \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                 \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                 \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                               \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                   \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                         \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                               \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                               \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                 \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                   \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                 \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                       \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                     \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                     \
  X(PFNGLPROGRAMUNIFORM1IPROC, ProgramUniform1i)                         \
  X(PFNGLPROGRAMUNIFORM1UIPROC, ProgramUniform1ui)                       \
  X(PFNGLPROGRAMUNIFORM1FPROC, ProgramUniform1f)                         \
  X(PFNGLPROGRAMUNIFORM2FPROC, ProgramUniform2f)                         \
  X(PFNGLPROGRAMUNIFORM3FPROC, ProgramUniform3f)                         \
  X(PFNGLPROGRAMUNIFORM4FPROC, ProgramUniform4f)                         \
  X(PFNGLPROGRAMUNIFORMMATRIX4FVPROC, ProgramUniformMatrix4fv)           \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                     \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                     \
  X(PFNGLCLEARPROC, Clear)                                               \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                     \
  X(PFNGLTEXTURESUBIMAGE3DPROC, TextureSubImage3D)                       \
  X(PFNGLCLEARTEXIMAGEPROC, ClearTexImage)                               \
  X(PFNGLCLEARTEXSUBIMAGEPROC, ClearTexSubImage)                         \
  X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                           \
  X(PFNGLBINDIMAGETEXTUREPROC, BindImageTexture)                         \
  X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                               \
  X(PFNGLPROGRAMUNIFORM2IPROC, ProgramUniform2i)                         \
  X(PFNGLBLITNAMEDFRAMEBUFFERPROC, BlitNamedFramebuffer)                 \
  X(PFNGLCREATESAMPLERSPROC, CreateSamplers)                             \
  X(PFNGLDELETESAMPLERSPROC, DeleteSamplers)                             \
  X(PFNGLSAMPLERPARAMETERIPROC, SamplerParameteri)                       \
  X(PFNGLBINDSAMPLERPROC, BindSampler)                                   \
  X(PFNGLCREATEQUERIESPROC, CreateQueries)                               \
  X(PFNGLDELETEQUERIESPROC, DeleteQueries)                               \
  X(PFNGLBEGINQUERYPROC, BeginQuery)                                     \
  X(PFNGLENDQUERYPROC, EndQuery)                                         \
  X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)

namespace photovr::gl::api {

#define PHOTOVR_GL_DECLARE(type, name) extern type name;
PHOTOVR_GL_FUNCTIONS(PHOTOVR_GL_DECLARE)
#undef PHOTOVR_GL_DECLARE

using ProcLoader = void* (*)(const char* name);
// Loads every entry point; returns the first one the implementation lacks, or "".
const char* load(ProcLoader loader);

}  // namespace photovr::gl::api
