/*
 * glfn.h — GL 4.5 entry points that libOSMesa does not export as symbols
 * (direct state access, glClipControl, glGetTextureImage): fetched once with
 * OSMesaGetProcAddress after the context is made current (sl_gl_init), and
 * called under their usual names through the macros below. Everything older
 * is linked from libOSMesa directly (GL_GLEXT_PROTOTYPES).
 */
#ifndef SL_GLFN_H
#define SL_GLFN_H
#include <GL/gl.h>
#include <GL/glext.h>

#define SL_GL_FUNCS(X)                                                   \
    X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, glCheckNamedFramebufferStatus) \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, glClearNamedFramebufferfv)       \
    X(PFNGLCLEARNAMEDFRAMEBUFFERUIVPROC, glClearNamedFramebufferuiv)     \
    X(PFNGLCLIPCONTROLPROC, glClipControl)                               \
    X(PFNGLCREATEBUFFERSPROC, glCreateBuffers)                           \
    X(PFNGLCREATEFRAMEBUFFERSPROC, glCreateFramebuffers)                 \
    X(PFNGLCREATERENDERBUFFERSPROC, glCreateRenderbuffers)               \
    X(PFNGLCREATETEXTURESPROC, glCreateTextures)                         \
    X(PFNGLCREATEVERTEXARRAYSPROC, glCreateVertexArrays)                 \
    X(PFNGLENABLEVERTEXARRAYATTRIBPROC, glEnableVertexArrayAttrib)       \
    X(PFNGLGETTEXTUREIMAGEPROC, glGetTextureImage)                       \
    X(PFNGLNAMEDBUFFERSTORAGEPROC, glNamedBufferStorage)                 \
    X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERPROC, glNamedFramebufferDrawBuffer) \
    X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, glNamedFramebufferDrawBuffers) \
    X(PFNGLNAMEDFRAMEBUFFERRENDERBUFFERPROC, glNamedFramebufferRenderbuffer) \
    X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, glNamedFramebufferTexture)       \
    X(PFNGLNAMEDRENDERBUFFERSTORAGEPROC, glNamedRenderbufferStorage)     \
    X(PFNGLTEXTURESTORAGE2DPROC, glTextureStorage2D)                     \
    X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, glVertexArrayAttribBinding)     \
    X(PFNGLVERTEXARRAYATTRIBFORMATPROC, glVertexArrayAttribFormat)       \
    X(PFNGLVERTEXARRAYELEMENTBUFFERPROC, glVertexArrayElementBuffer)     \
    X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, glVertexArrayVertexBuffer)      \
    X(PFNGLGETQUERYOBJECTUI64VPROC, glGetQueryObjectui64v)               \
    X(PFNGLUNIFORM1DPROC, glUniform1d)                                   \
    X(PFNGLBINDTEXTUREUNITPROC, glBindTextureUnit)                       \
    X(PFNGLTEXTURESUBIMAGE2DPROC, glTextureSubImage2D)                   \
    X(PFNGLTEXTUREPARAMETERIPROC, glTextureParameteri)

#define SL_GL_DECL(type, name) extern type sl_##name;
SL_GL_FUNCS(SL_GL_DECL)
#undef SL_GL_DECL

#define glCheckNamedFramebufferStatus sl_glCheckNamedFramebufferStatus
#define glClearNamedFramebufferfv sl_glClearNamedFramebufferfv
#define glClearNamedFramebufferuiv sl_glClearNamedFramebufferuiv
#define glClipControl sl_glClipControl
#define glCreateBuffers sl_glCreateBuffers
#define glCreateFramebuffers sl_glCreateFramebuffers
#define glCreateRenderbuffers sl_glCreateRenderbuffers
#define glCreateTextures sl_glCreateTextures
#define glCreateVertexArrays sl_glCreateVertexArrays
#define glEnableVertexArrayAttrib sl_glEnableVertexArrayAttrib
#define glGetTextureImage sl_glGetTextureImage
#define glNamedBufferStorage sl_glNamedBufferStorage
#define glNamedFramebufferDrawBuffer sl_glNamedFramebufferDrawBuffer
#define glNamedFramebufferDrawBuffers sl_glNamedFramebufferDrawBuffers
#define glNamedFramebufferRenderbuffer sl_glNamedFramebufferRenderbuffer
#define glNamedFramebufferTexture sl_glNamedFramebufferTexture
#define glNamedRenderbufferStorage sl_glNamedRenderbufferStorage
#define glTextureStorage2D sl_glTextureStorage2D
#define glVertexArrayAttribBinding sl_glVertexArrayAttribBinding
#define glVertexArrayAttribFormat sl_glVertexArrayAttribFormat
#define glVertexArrayElementBuffer sl_glVertexArrayElementBuffer
#define glVertexArrayVertexBuffer sl_glVertexArrayVertexBuffer
#define glGetQueryObjectui64v sl_glGetQueryObjectui64v
#define glUniform1d sl_glUniform1d
#define glBindTextureUnit sl_glBindTextureUnit
#define glTextureSubImage2D sl_glTextureSubImage2D
#define glTextureParameteri sl_glTextureParameteri

/* Returns the name of the first entry point not found, or NULL. */
const char *sl_glfn_load(void);

#endif
