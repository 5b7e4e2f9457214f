/*
 * glfn.h — every GL entry point shadowlab calls, fetched once through the
 * backend's proc-address lookup (OSMesaGetProcAddress or eglGetProcAddress)
 * after the context is made current (sl_gl_init), and called under the usual
 * names through the macros below.
 *
 * Why all of them, not only the 4.5 ones: no gl* symbol is linked. libOSMesa
 * exports gl* symbols that dispatch through Mesa's own libglapi, libOpenGL
 * (glvnd) exports the same names dispatching through libGLdispatch; a binary
 * with both backends can link only one set, and the wrong one renders into
 * nothing (or crashes) under the other backend, e.g. under NVIDIA's EGL.
 * Both lookups return core entry points (EGL_KHR_get_all_proc_addresses;
 * OSMesa always), so one list serves both. A gl call missing from this list
 * fails to link (the layout test builds without libGL on the link line).
 * The types come from the prototypes (GL_GLEXT_PROTOTYPES) via __typeof__.
 */
#ifndef SL_GLFN_H
#define SL_GLFN_H
#include <GL/gl.h>
#include <GL/glext.h>

#define SL_GL_FUNCS(X) \
    X(glAttachShader) \
    X(glBeginQuery) \
    X(glBindFramebuffer) \
    X(glBindImageTexture) \
    X(glBindTextureUnit) \
    X(glBindVertexArray) \
    X(glCheckNamedFramebufferStatus) \
    X(glClearNamedFramebufferfv) \
    X(glClearNamedFramebufferuiv) \
    X(glClipControl) \
    X(glCompileShader) \
    X(glCreateBuffers) \
    X(glCreateFramebuffers) \
    X(glCreateProgram) \
    X(glCreateRenderbuffers) \
    X(glCreateShader) \
    X(glCreateTextures) \
    X(glCreateVertexArrays) \
    X(glCullFace) \
    X(glDeleteBuffers) \
    X(glDeleteFramebuffers) \
    X(glDeleteProgram) \
    X(glDeleteQueries) \
    X(glDeleteRenderbuffers) \
    X(glDeleteShader) \
    X(glDeleteTextures) \
    X(glDeleteVertexArrays) \
    X(glDepthFunc) \
    X(glDisable) \
    X(glDrawArrays) \
    X(glDrawElements) \
    X(glEnable) \
    X(glEnableVertexArrayAttrib) \
    X(glEndQuery) \
    X(glFinish) \
    X(glFlush) \
    X(glFrontFace) \
    X(glGenQueries) \
    X(glGenerateTextureMipmap) \
    X(glGetError) \
    X(glGetGraphicsResetStatus) \
    X(glGetIntegerv) \
    X(glGetProgramInfoLog) \
    X(glGetProgramiv) \
    X(glGetQueryObjectui64v) \
    X(glGetShaderInfoLog) \
    X(glGetShaderiv) \
    X(glGetString) \
    X(glGetTextureImage) \
    X(glGetUniformLocation) \
    X(glLinkProgram) \
    X(glNamedBufferStorage) \
    X(glNamedFramebufferDrawBuffer) \
    X(glNamedFramebufferDrawBuffers) \
    X(glNamedFramebufferRenderbuffer) \
    X(glNamedFramebufferTexture) \
    X(glNamedRenderbufferStorage) \
    X(glPixelStorei) \
    X(glScissor) \
    X(glShaderSource) \
    X(glTextureParameteri) \
    X(glTextureStorage2D) \
    X(glTextureSubImage2D) \
    X(glUniform1d) \
    X(glUniform1f) \
    X(glUniform1i) \
    X(glUniform1ui) \
    X(glUniform2f) \
    X(glUniform2i) \
    X(glUniform3f) \
    X(glUniformMatrix4fv) \
    X(glUseProgram) \
    X(glVertexArrayAttribBinding) \
    X(glVertexArrayAttribFormat) \
    X(glVertexArrayElementBuffer) \
    X(glVertexArrayVertexBuffer) \
    X(glViewport)

#define SL_GL_DECL(name) extern __typeof__(&name) sl_##name;
SL_GL_FUNCS(SL_GL_DECL)
#undef SL_GL_DECL

#define glAttachShader sl_glAttachShader
#define glBeginQuery sl_glBeginQuery
#define glBindFramebuffer sl_glBindFramebuffer
#define glBindImageTexture sl_glBindImageTexture
#define glBindTextureUnit sl_glBindTextureUnit
#define glBindVertexArray sl_glBindVertexArray
#define glCheckNamedFramebufferStatus sl_glCheckNamedFramebufferStatus
#define glClearNamedFramebufferfv sl_glClearNamedFramebufferfv
#define glClearNamedFramebufferuiv sl_glClearNamedFramebufferuiv
#define glClipControl sl_glClipControl
#define glCompileShader sl_glCompileShader
#define glCreateBuffers sl_glCreateBuffers
#define glCreateFramebuffers sl_glCreateFramebuffers
#define glCreateProgram sl_glCreateProgram
#define glCreateRenderbuffers sl_glCreateRenderbuffers
#define glCreateShader sl_glCreateShader
#define glCreateTextures sl_glCreateTextures
#define glCreateVertexArrays sl_glCreateVertexArrays
#define glCullFace sl_glCullFace
#define glDeleteBuffers sl_glDeleteBuffers
#define glDeleteFramebuffers sl_glDeleteFramebuffers
#define glDeleteProgram sl_glDeleteProgram
#define glDeleteQueries sl_glDeleteQueries
#define glDeleteRenderbuffers sl_glDeleteRenderbuffers
#define glDeleteShader sl_glDeleteShader
#define glDeleteTextures sl_glDeleteTextures
#define glDeleteVertexArrays sl_glDeleteVertexArrays
#define glDepthFunc sl_glDepthFunc
#define glDisable sl_glDisable
#define glDrawArrays sl_glDrawArrays
#define glDrawElements sl_glDrawElements
#define glEnable sl_glEnable
#define glEnableVertexArrayAttrib sl_glEnableVertexArrayAttrib
#define glEndQuery sl_glEndQuery
#define glFinish sl_glFinish
#define glFlush sl_glFlush
#define glFrontFace sl_glFrontFace
#define glGenQueries sl_glGenQueries
#define glGenerateTextureMipmap sl_glGenerateTextureMipmap
#define glGetError sl_glGetError
#define glGetGraphicsResetStatus sl_glGetGraphicsResetStatus
#define glGetIntegerv sl_glGetIntegerv
#define glGetProgramInfoLog sl_glGetProgramInfoLog
#define glGetProgramiv sl_glGetProgramiv
#define glGetQueryObjectui64v sl_glGetQueryObjectui64v
#define glGetShaderInfoLog sl_glGetShaderInfoLog
#define glGetShaderiv sl_glGetShaderiv
#define glGetString sl_glGetString
#define glGetTextureImage sl_glGetTextureImage
#define glGetUniformLocation sl_glGetUniformLocation
#define glLinkProgram sl_glLinkProgram
#define glNamedBufferStorage sl_glNamedBufferStorage
#define glNamedFramebufferDrawBuffer sl_glNamedFramebufferDrawBuffer
#define glNamedFramebufferDrawBuffers sl_glNamedFramebufferDrawBuffers
#define glNamedFramebufferRenderbuffer sl_glNamedFramebufferRenderbuffer
#define glNamedFramebufferTexture sl_glNamedFramebufferTexture
#define glNamedRenderbufferStorage sl_glNamedRenderbufferStorage
#define glPixelStorei sl_glPixelStorei
#define glScissor sl_glScissor
#define glShaderSource sl_glShaderSource
#define glTextureParameteri sl_glTextureParameteri
#define glTextureStorage2D sl_glTextureStorage2D
#define glTextureSubImage2D sl_glTextureSubImage2D
#define glUniform1d sl_glUniform1d
#define glUniform1f sl_glUniform1f
#define glUniform1i sl_glUniform1i
#define glUniform1ui sl_glUniform1ui
#define glUniform2f sl_glUniform2f
#define glUniform2i sl_glUniform2i
#define glUniform3f sl_glUniform3f
#define glUniformMatrix4fv sl_glUniformMatrix4fv
#define glUseProgram sl_glUseProgram
#define glVertexArrayAttribBinding sl_glVertexArrayAttribBinding
#define glVertexArrayAttribFormat sl_glVertexArrayAttribFormat
#define glVertexArrayElementBuffer sl_glVertexArrayElementBuffer
#define glVertexArrayVertexBuffer sl_glVertexArrayVertexBuffer
#define glViewport sl_glViewport

/* A proc-address lookup (the backend's), as a plain function. */
typedef void (*sl_glproc)(void);
typedef sl_glproc (*sl_glfn_getproc)(const char *name);

/* Fills every entry point through getproc. Returns the name of the first
 * entry point not found, or NULL. */
const char *sl_glfn_load(sl_glfn_getproc getproc);

#endif
