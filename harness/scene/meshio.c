/*
 * meshio.c — model files into sl_mesh through assimp's C API, and welding.
 *
 * Invariants:
 * - Nothing assimp returns is trusted: every pointer is checked before use,
 *   every face index is checked against its mesh's vertex count, node mesh
 *   references against the scene's mesh count, and the node tree is walked
 *   with an explicit depth limit (no recursion a hostile file can exhaust).
 *   assimp's own post-processing only runs on a scene whose pointers, face
 *   indices and coordinates passed these checks (see load_direct).
 * - assimp only ever runs in the reader's child (meshio_child.c: limits, a
 *   crash or a hang is an error naming the file), after the file's own bytes
 *   were checked (meshio_check.c: declared vs present counts, indices); the
 *   parent checks the child's mesh again before anything is appended.
 * - A file is built into a private mesh, checked and welded there, and only
 *   appended to the caller's mesh when everything succeeded, so an error
 *   leaves the caller's mesh exactly as it was (same counts, same bytes).
 * - Only vertices referenced by a triangle are copied, so points, lines and
 *   unused vertices never widen a scene's bounds.
 * - sl_mesh_weld keeps what sl_scene_from_mesh accepts: a triangle survives
 *   only if its double-precision normal has a length > 0 computed exactly as
 *   scene.c computes it, so a welded mesh never fails there for zero area.
 */
#include "gen.h"
#include "meshio.h"
#include "meshio_check.h"
#include "meshio_child.h"
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "util.h"

/* Deeper node trees than this are treated as corrupt. Real files nest a few
 * dozen levels; the limit only bounds the walk's stack. */
#define MESHIO_MAX_DEPTH 256

/* ---------------------------------------------------------------- welding */

static int reserve(void **p, uint32_t *cap, uint32_t need, size_t elem)
{
    if (need <= *cap)
        return 1;
    uint64_t c = *cap ? *cap : 256;
    while (c < need)
        c *= 2;
    if (c > 0xffffffffu)
        c = need;
    void *q = realloc(*p, (size_t)c * elem);
    if (!q)
        return 0;
    *p = q;
    *cap = (uint32_t)c;
    return 1;
}

static uint32_t hash3(const uint32_t k[3])
{
    uint64_t h = 0x9e3779b97f4a7c15ull;
    for (int i = 0; i < 3; i++) {
        h ^= k[i];
        h *= 0xff51afd7ed558ccdull;
        h ^= h >> 32;
    }
    return (uint32_t)h;
}

static void float_bits(const float *p, uint32_t k[3])
{
    memcpy(k, p, 3 * sizeof(float));
}

/* The scene's own test (sl_tri_normal_d): the weld drops exactly what the
 * scene would reject. */
static int tri_has_area(const float *a, const float *b, const float *c)
{
    double n[3];
    return sl_tri_normal_d(a, b, c, n) > 0.0;
}

/*
 * Vertices keep their first occurrence's place: vertex i becomes the first
 * j <= i with the same bits, so positions are compacted in place (j never
 * overtakes i). -0.0 is turned into +0.0 first: the same point reached by two
 * transforms may carry either sign, and splitting a vertex on a sign bit
 * would open an edge. Vertices no triangle uses are kept (welded like the
 * others). Triangles indexing a missing vertex are dropped with the
 * degenerate ones. On allocation failure m is untouched and m->oom is set.
 */
uint32_t sl_mesh_weld(struct sl_mesh *m)
{
    if (!m || m->nv == 0) {
        if (m && m->nt) {   /* every triangle indexes a missing vertex */
            uint32_t n = m->nt;
            m->nt = 0;
            return n;
        }
        return 0;
    }
    uint64_t cap = 16;
    while (cap < 2ull * m->nv)
        cap *= 2;
    uint32_t *table = malloc((size_t)cap * sizeof *table);
    uint32_t *remap = malloc((size_t)m->nv * sizeof *remap);
    if (!table || !remap) {
        free(table);
        free(remap);
        m->oom = 1;
        return 0;
    }
    memset(table, 0xff, (size_t)cap * sizeof *table);
    uint32_t mask = (uint32_t)(cap - 1), nu = 0;
    for (uint32_t i = 0; i < m->nv; i++) {
        float *p = m->pos + 3 * (size_t)i;
        for (int k = 0; k < 3; k++)
            if (p[k] == 0.0f)
                p[k] = 0.0f;
        uint32_t key[3];
        float_bits(p, key);
        uint32_t h = hash3(key) & mask;
        for (;;) {
            uint32_t j = table[h];
            if (j == 0xffffffffu) {
                table[h] = nu;
                if (nu != i)
                    memcpy(m->pos + 3 * (size_t)nu, p, 3 * sizeof(float));
                remap[i] = nu++;
                break;
            }
            uint32_t kj[3];
            float_bits(m->pos + 3 * (size_t)j, kj);
            if (kj[0] == key[0] && kj[1] == key[1] && kj[2] == key[2]) {
                remap[i] = j;
                break;
            }
            h = (h + 1) & mask;
        }
    }
    uint32_t nv_old = m->nv, kept = 0;
    m->nv = nu;
    for (uint32_t t = 0; t < m->nt; t++) {
        const uint32_t *ix = m->idx + 3 * (size_t)t;
        if (ix[0] >= nv_old || ix[1] >= nv_old || ix[2] >= nv_old)
            continue;
        uint32_t a = remap[ix[0]], b = remap[ix[1]], c = remap[ix[2]];
        if (a == b || b == c || a == c)
            continue;
        if (!tri_has_area(m->pos + 3 * (size_t)a, m->pos + 3 * (size_t)b, m->pos + 3 * (size_t)c))
            continue;
        uint32_t *o = m->idx + 3 * (size_t)kept++;
        o[0] = a; o[1] = b; o[2] = c;
    }
    uint32_t dropped = m->nt - kept;
    m->nt = kept;
    free(table);
    free(remap);
    return dropped;
}

/* ---------------------------------------------------------------- loading */

/* Column-major 4x4 in double: out = a * b. */
static void mat_mul(double out[16], const double a[16], const double b[16])
{
    double r[16];
    for (int c = 0; c < 4; c++)
        for (int rr = 0; rr < 4; rr++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++)
                s += a[k * 4 + rr] * b[c * 4 + k];
            r[c * 4 + rr] = s;
        }
    memcpy(out, r, sizeof r);
}

/* aiMatrix4x4 is row-major (a1..a4 is the first row, translation in a4, b4,
 * c4); ours are column-major like cglm. */
static void mat_from_ai(double out[16], const struct aiMatrix4x4 *t)
{
    const ai_real r[4][4] = {
        {t->a1, t->a2, t->a3, t->a4},
        {t->b1, t->b2, t->b3, t->b4},
        {t->c1, t->c2, t->c3, t->c4},
        {t->d1, t->d2, t->d3, t->d4},
    };
    for (int row = 0; row < 4; row++)
        for (int col = 0; col < 4; col++)
            out[col * 4 + row] = (double)r[row][col];
}

struct load_ctx {
    const char               *path;
    const struct aiScene     *sc;
    struct sl_mesh           *tmp;
    struct sl_mesh_load_stats st;
    uint32_t                 *vmap;      /* per assimp vertex: tmp index + 1, 0 = not yet */
    uint32_t                  vmap_cap;
    struct sl_diag           *d;
};

static enum sl_err append_mesh(struct load_ctx *c, const struct aiMesh *am, const double M[16])
{
    if (am->mNumFaces == 0)
        return SL_OK;
    if (!am->mFaces)
        return sl_fail(c->d, SL_E_SCENE, c->path, 0, NULL, "corrupt file: mesh without faces array");
    if (am->mNumVertices && !am->mVertices)
        return sl_fail(c->d, SL_E_SCENE, c->path, 0, NULL, "corrupt file: mesh without vertex array");
    if (am->mNumVertices > c->vmap_cap) {
        uint32_t *v = realloc(c->vmap, (size_t)am->mNumVertices * sizeof *v);
        if (!v)
            return sl_fail(c->d, SL_E_NOMEM, c->path, 0, NULL, "mesh of %u vertices", am->mNumVertices);
        c->vmap = v;
        c->vmap_cap = am->mNumVertices;
    }
    if (am->mNumVertices)
        memset(c->vmap, 0, (size_t)am->mNumVertices * sizeof *c->vmap);
    c->st.meshes++;   /* per node instance: a mesh placed by two nodes counts twice */
    for (unsigned f = 0; f < am->mNumFaces; f++) {
        const struct aiFace *face = &am->mFaces[f];
        if (face->mNumIndices != 3) {
            /* points and lines (and anything Triangulate left, which it
             * should not) carry no surface */
            c->st.skipped_prims++;
            continue;
        }
        if (!face->mIndices)
            return sl_fail(c->d, SL_E_SCENE, c->path, 0, NULL, "corrupt file: face without indices");
        uint32_t tri[3];
        for (int k = 0; k < 3; k++) {
            unsigned vi = face->mIndices[k];
            if (vi >= am->mNumVertices)
                return sl_fail(c->d, SL_E_SCENE, c->path, 0, NULL,
                               "corrupt file: face %u indexes vertex %u of %u", f, vi, am->mNumVertices);
            if (!c->vmap[vi]) {
                const struct aiVector3D *v = &am->mVertices[vi];
                double p[3] = {(double)v->x, (double)v->y, (double)v->z};
                /* a projective last row is honoured; w = 0 gives inf below */
                double w = M[3] * p[0] + M[7] * p[1] + M[11] * p[2] + M[15];
                float q[3];
                int finite = 1;
                for (int r = 0; r < 3; r++) {
                    double s = M[r] * p[0] + M[4 + r] * p[1] + M[8 + r] * p[2] + M[12 + r];
                    if (w != 1.0)
                        s /= w;
                    /* beyond FLT_MAX the float would be inf */
                    if (!(fabs(s) <= FLT_MAX))
                        finite = 0;
                    q[r] = finite ? (float)s : 0.0f;
                }
                if (!finite)
                    return sl_fail(c->d, SL_E_SCENE, c->path, 0, NULL,
                                   "non-finite vertex (vertex %u of mesh '%.*s')", vi,
                                   (int)(am->mName.length < 64 ? am->mName.length : 64),
                                   am->mName.data);
                if (c->tmp->nv >= MESHIO_MAX_ELEMS)
                    return sl_fail(c->d, SL_E_SCENE, c->path, 0, NULL, "too many vertices");
                c->vmap[vi] = sl_mesh_vertex(c->tmp, q[0], q[1], q[2]) + 1;
                if (c->tmp->oom)
                    return sl_fail(c->d, SL_E_NOMEM, c->path, 0, NULL, "out of memory reading vertices");
            }
            tri[k] = c->vmap[vi] - 1;
        }
        if (c->tmp->nt >= MESHIO_MAX_ELEMS)
            return sl_fail(c->d, SL_E_SCENE, c->path, 0, NULL, "too many triangles");
        sl_mesh_tri(c->tmp, tri[0], tri[1], tri[2]);
        if (c->tmp->oom)
            return sl_fail(c->d, SL_E_NOMEM, c->path, 0, NULL, "out of memory reading triangles");
    }
    return SL_OK;
}

/* What assimp's reader produced, before any post-processing step reads it. */
static enum sl_err check_raw(const struct aiScene *sc, const char *path, struct sl_diag *d)
{
    /* assimp's post-processing crashes on a scene with no mesh or an empty
     * one (an STL 'solid a / endsolid a' gives one) */
    if (sc->mNumMeshes == 0)
        return sl_fail(d, SL_E_SCENE, path, 0, NULL, "no triangles (the file holds no mesh)");
    if (!sc->mMeshes)
        return sl_fail(d, SL_E_SCENE, path, 0, NULL, "corrupt file: scene without mesh list");
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        const struct aiMesh *am = sc->mMeshes[i];
        if (!am)
            return sl_fail(d, SL_E_SCENE, path, 0, NULL, "corrupt file: mesh %u missing", i);
        if ((am->mNumVertices && !am->mVertices) || (am->mNumFaces && !am->mFaces))
            return sl_fail(d, SL_E_SCENE, path, 0, NULL, "corrupt file: mesh %u without data", i);
        if (am->mNumVertices == 0 || am->mNumFaces == 0)
            return sl_fail(d, SL_E_SCENE, path, 0, NULL,
                           "no triangles (mesh %u has %u vertices and %u faces)", i,
                           am->mNumVertices, am->mNumFaces);
        for (unsigned v = 0; v < am->mNumVertices; v++) {
            const struct aiVector3D *p = &am->mVertices[v];
            if (!isfinite(p->x) || !isfinite(p->y) || !isfinite(p->z))
                return sl_fail(d, SL_E_SCENE, path, 0, NULL,
                               "non-finite vertex (vertex %u of mesh %u '%.*s')", v, i,
                               (int)(am->mName.length < 64 ? am->mName.length : 64),
                               am->mName.data);
        }
        for (unsigned f = 0; f < am->mNumFaces; f++) {
            const struct aiFace *fc = &am->mFaces[f];
            if (fc->mNumIndices == 0 || !fc->mIndices)
                return sl_fail(d, SL_E_SCENE, path, 0, NULL,
                               "corrupt file: face %u of mesh %u has no indices", f, i);
            for (unsigned k = 0; k < fc->mNumIndices; k++)
                if (fc->mIndices[k] >= am->mNumVertices)
                    return sl_fail(d, SL_E_SCENE, path, 0, NULL,
                                   "corrupt file: face %u of mesh %u indexes vertex %u of %u", f,
                                   i, fc->mIndices[k], am->mNumVertices);
        }
    }
    return SL_OK;
}

/* Depth-first over the node tree with an explicit stack; a node's matrix is
 * xform * (ancestors' transforms) * its own. */
static enum sl_err walk_nodes(struct load_ctx *c, const double X[16])
{
    struct frame { const struct aiNode *n; double M[16]; unsigned next_child; };
    struct frame *stack = malloc(MESHIO_MAX_DEPTH * sizeof *stack);
    if (!stack)
        return sl_fail(c->d, SL_E_NOMEM, c->path, 0, NULL, "node stack");
    enum sl_err e = SL_OK;
    int top = 0;
    double L[16];
    mat_from_ai(L, &c->sc->mRootNode->mTransformation);
    stack[0].n = c->sc->mRootNode;
    mat_mul(stack[0].M, X, L);
    stack[0].next_child = 0;
    /* meshes of a node are appended when the node is entered */
    for (;;) {
        struct frame *fr = &stack[top];
        const struct aiNode *n = fr->n;
        if (fr->next_child == 0) {
            if (n->mNumMeshes && !n->mMeshes) {
                e = sl_fail(c->d, SL_E_SCENE, c->path, 0, NULL, "corrupt file: node without mesh list");
                break;
            }
            for (unsigned i = 0; i < n->mNumMeshes; i++) {
                unsigned mi = n->mMeshes[i];
                if (mi >= c->sc->mNumMeshes || !c->sc->mMeshes || !c->sc->mMeshes[mi]) {
                    e = sl_fail(c->d, SL_E_SCENE, c->path, 0, NULL,
                                "corrupt file: node references missing mesh %u", mi);
                    break;
                }
                e = append_mesh(c, c->sc->mMeshes[mi], fr->M);
                if (e)
                    break;
            }
            if (e)
                break;
            if (n->mNumChildren && !n->mChildren) {
                e = sl_fail(c->d, SL_E_SCENE, c->path, 0, NULL, "corrupt file: node without child list");
                break;
            }
        }
        if (fr->next_child < n->mNumChildren) {
            const struct aiNode *ch = n->mChildren[fr->next_child++];
            if (!ch) {
                e = sl_fail(c->d, SL_E_SCENE, c->path, 0, NULL, "corrupt file: missing child node");
                break;
            }
            if (top + 1 >= MESHIO_MAX_DEPTH) {
                e = sl_fail(c->d, SL_E_SCENE, c->path, 0, NULL,
                            "node tree deeper than %d levels", MESHIO_MAX_DEPTH);
                break;
            }
            struct frame *nf = &stack[++top];
            mat_from_ai(L, &ch->mTransformation);
            mat_mul(nf->M, stack[top - 1].M, L);
            nf->n = ch;
            nf->next_child = 0;
            continue;
        }
        if (top == 0)
            break;
        top--;
    }
    free(stack);
    return e;
}

/* Copy src after dst's contents. All memory is reserved first, so on failure
 * dst keeps its contents (it may keep a larger capacity). */
static int mesh_append(struct sl_mesh *dst, const struct sl_mesh *src)
{
    if ((uint64_t)dst->nv + src->nv > MESHIO_MAX_ELEMS ||
        (uint64_t)dst->nt + src->nt > MESHIO_MAX_ELEMS)
        return 0;
    if (!reserve((void **)&dst->pos, &dst->cap_v, dst->nv + src->nv, 3 * sizeof(float)) ||
        !reserve((void **)&dst->idx, &dst->cap_t, dst->nt + src->nt, 3 * sizeof(uint32_t)))
        return 0;
    memcpy(dst->pos + 3 * (size_t)dst->nv, src->pos, (size_t)src->nv * 3 * sizeof(float));
    uint32_t *o = dst->idx + 3 * (size_t)dst->nt;
    for (size_t i = 0; i < 3 * (size_t)src->nt; i++)
        o[i] = src->idx[i] + dst->nv;
    dst->nv += src->nv;
    dst->nt += src->nt;
    return 1;
}

/* assimp logs some errors and carries on with a repaired scene (an OFF face
 * index out of range); the first error logged about an index or a range
 * makes the file fail. Other logged errors (a missing material) are about
 * things we never read. Its glTF 2 reader drops faces whose indices reach
 * beyond the primitive's POSITION accessor with only a warning: the rest
 * loads (silently wrong), or a mesh left with no face fails as "has no
 * faces" (and one left with only degenerate faces as "only zero-area
 * triangles"); that warning makes the file fail too, with its real reason. */
static char g_ai_error[256];
static int  g_ai_dropped;

static void ai_log(const char *msg, char *user)
{
    (void)user;
    if (!strncmp(msg, "Warn", 4) && strstr(msg, "out-of-range indices")) {
        g_ai_dropped = 1;
        return;
    }
    if (g_ai_error[0] || strncmp(msg, "Error", 5) != 0 ||
        !(strstr(msg, "ndex") || strstr(msg, "range")))
        return;
    const char *m = strstr(msg, ": ");
    snprintf(g_ai_error, sizeof g_ai_error, "%s", m ? m + 2 : msg);
    size_t n = strlen(g_ai_error);
    while (n && (g_ai_error[n - 1] == '\n' || g_ai_error[n - 1] == '\r'))
        g_ai_error[--n] = 0;
}

/* The glTF reader's dropped faces (see ai_log), naming the mesh where the
 * scene has one (assimp's warning names none) or assimp's own failure. */
static enum sl_err dropped_faces(const struct aiScene *sc, const char *path, struct sl_diag *d)
{
    const char *why = sc ? NULL : aiGetErrorString();
    const struct aiMesh *am = sc && sc->mNumMeshes == 1 && sc->mMeshes ? sc->mMeshes[0] : NULL;
    return sl_fail(d, SL_E_SCENE, path, 0, NULL, "corrupt file: face index out of range%s%.*s%s "
                   "(a primitive's indices name vertices its POSITION accessor does not hold)%s%s",
                   am ? " in mesh '" : "", am ? (int)(am->mName.length < 64 ? am->mName.length : 64) : 0,
                   am ? am->mName.data : "", am ? "'" : "", why && why[0] ? ": " : "",
                   why && why[0] ? why : "");
}

static enum sl_err load_assimp(struct sl_mesh *m, const char *path, const float xform[16],
                               struct sl_mesh_load_stats *st, struct sl_diag *d);
static enum sl_err read_scene(struct sl_mesh *m, const char *path, const void *data, size_t size,
                              const float xform[16], struct sl_mesh_load_stats *st, struct sl_diag *d);

/* In the reader's process: assimp reads the file, its result is checked and
 * welded into m. sl_mesh_load_file runs this in a child (meshio_child.c);
 * sl_mesh_load_file_here in this process, input after input, so the log's
 * state starts afresh and its stream is detached each time. */
static enum sl_err load_direct(struct sl_mesh *m, const char *path, const float xform[16],
                               struct sl_mesh_load_stats *st, struct sl_diag *d)
{
    g_ai_error[0] = '\0';
    g_ai_dropped = 0;
    struct aiLogStream ls = {.callback = ai_log, .user = NULL};
    aiAttachLogStream(&ls);
    enum sl_err e = load_assimp(m, path, xform, st, d);
    aiDetachAllLogStreams();
    return e;
}

static enum sl_err load_assimp(struct sl_mesh *m, const char *path, const float xform[16],
                               struct sl_mesh_load_stats *st, struct sl_diag *d)
{
    if (!m || !path)
        return sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "sl_mesh_load_file: NULL argument");
    /* Opened here first so a missing or unreadable file gets the system's
     * reason rather than a format guess, and an empty one says so. */
    int fd;
    struct sl_diag od;
    if (!sl_file_type_bad(path) && access(path, R_OK) != 0)
        return sl_fail(d, SL_E_SCENE, path, 0, NULL, "cannot open: %s", strerror(errno));
    if (sl_open_regular(path, &fd, NULL, &od))   /* no FIFO or device: assimp would block or never end */
        return sl_fail(d, SL_E_SCENE, path, 0, NULL, "%s", od.msg);
    unsigned char c0;
    ssize_t got = read(fd, &c0, 1);
    int rerr = got < 0 ? errno : 0;
    close(fd);
    if (rerr)
        return sl_fail(d, SL_E_SCENE, path, 0, NULL, "cannot read: %s", strerror(rerr));
    if (got == 0)
        return sl_fail(d, SL_E_SCENE, path, 0, NULL, "no triangles (empty file)");
    return read_scene(m, path, NULL, 0, xform, st, d);
}

/* The file at path (data NULL), or size bytes at data named path (its
 * extension is assimp's format hint): checked, read, checked, welded. */
static enum sl_err read_scene(struct sl_mesh *m, const char *path, const void *data, size_t size,
                              const float xform[16], struct sl_mesh_load_stats *st, struct sl_diag *d)
{

    /*
     * The file is read without post-processing first and checked (pointers,
     * face index ranges, finite coordinates): assimp's readers can hand back
     * out-of-range indices from a truncated file (a cut binary PLY does),
     * and its post-processing steps index with them unchecked (a crash, not
     * an error), while NaN keys break the sorts JoinIdenticalVertices uses.
     * Only a scene that passed is post-processed:
     * - Triangulate: polygons become triangles (points and lines stay, and
     *   are skipped and counted).
     * - JoinIdenticalVertices: formats that store a triangle soup (STL, OBJ
     *   corners) arrive indexed, which keeps the temporary mesh and our weld
     *   small; our weld then joins what it cannot (seams where normals or
     *   texture coordinates differ, and across meshes).
     * - SortByPType: one primitive type per mesh, so point and line meshes
     *   are recognised whole.
     * Not asked for: ValidateDataStructure (it also rejects files over
     * materials and animations we never read; we check every field we do
     * read), FindDegenerates (it would turn zero-area triangles into lines
     * before we could count them), PreTransformVertices (we apply node
     * transforms ourselves, in double, composed with xform), and anything
     * that generates normals or tangents (the scene computes face normals).
     */
    enum sl_err e = data ? sl_mesh_precheck_mem(data, size, path, d) : sl_mesh_precheck(path, d);
    if (e)
        return e;
    const char *dot = strrchr(path, '.');
    const struct aiScene *sc = data ? aiImportFileFromMemory(data, (unsigned)size, 0, dot ? dot + 1 : "")
                                    : aiImportFile(path, 0);
    if (g_ai_dropped) {
        e = dropped_faces(sc, path, d);
        if (sc)
            aiReleaseImport(sc);
        return e;
    }
    if (sc && g_ai_error[0]) {
        aiReleaseImport(sc);
        return sl_fail(d, SL_E_SCENE, path, 0, NULL, "corrupt file: %s", g_ai_error);
    }
    if (!sc) {
        const char *why = aiGetErrorString();
        return sl_fail(d, SL_E_SCENE, path, 0, NULL, "%s",
                       why && why[0] ? why : "assimp could not import the file");
    }
    e = check_raw(sc, path, d);
    if (e) {
        aiReleaseImport(sc);
        return e;
    }
    const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                           aiProcess_SortByPType;
    const struct aiScene *pp = aiApplyPostProcessing(sc, flags);
    if (!pp) {   /* assimp has released sc */
        const char *why = aiGetErrorString();
        return sl_fail(d, SL_E_SCENE, path, 0, NULL, "%s",
                       why && why[0] ? why : "assimp post-processing failed");
    }
    sc = pp;
    struct sl_mesh tmp = {0};
    struct load_ctx c = {.path = path, .sc = sc, .tmp = &tmp, .d = d};
    double X[16];
    for (int i = 0; i < 16; i++)
        X[i] = xform ? (double)xform[i] : (i % 5 == 0 ? 1.0 : 0.0);
    for (int i = 0; i < 16 && xform; i++)
        if (!isfinite(xform[i]))
            e = sl_fail(d, SL_E_SCENE, path, 0, NULL, "non-finite transform");
    if (!e && !sc->mRootNode)
        e = sl_fail(d, SL_E_SCENE, path, 0, NULL, "no triangles (no node tree)");
    if (!e)
        e = walk_nodes(&c, X);
    free(c.vmap);
    aiReleaseImport(sc);

    uint32_t read = tmp.nt, dropped = 0;
    if (!e && read == 0)
        e = sl_fail(d, SL_E_SCENE, path, 0, NULL, "no triangles");
    if (!e) {
        dropped = sl_mesh_weld(&tmp);
        if (tmp.oom)
            e = sl_fail(d, SL_E_NOMEM, path, 0, NULL, "out of memory welding");
        else if (tmp.nt == 0)
            e = sl_fail(d, SL_E_SCENE, path, 0, NULL, "only zero-area triangles (%u)", read);
    }
    if (!e && !mesh_append(m, &tmp))
        e = sl_fail(d, SL_E_NOMEM, path, 0, NULL, "out of memory appending %u triangles", tmp.nt);
    if (!e && st) {
        c.st.triangles = tmp.nt;
        c.st.vertices = tmp.nv;
        c.st.degenerate = dropped;
        *st = c.st;
    }
    sl_mesh_free(&tmp);
    return e;
}

static enum sl_err load_file(struct sl_mesh *m, const char *path, const float xform[16],
                             struct sl_mesh_load_stats *st, int in_child, struct sl_diag *d)
{
    if (!m || !path)
        return sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "sl_mesh_load_file: NULL argument");
    struct sl_mesh got = {0};
    struct sl_mesh_load_stats s;
    memset(&s, 0, sizeof s);
    enum sl_err e = in_child ? sl_mesh_read_in_child(load_direct, path, xform, &got, &s, d)
                             : load_direct(&got, path, xform, &s, d);
    if (!e && !mesh_append(m, &got))
        e = sl_fail(d, SL_E_NOMEM, path, 0, NULL, "out of memory appending %u triangles", got.nt);
    if (!e && st)
        *st = s;
    sl_mesh_free(&got);
    return e;
}

enum sl_err sl_mesh_load_file(struct sl_mesh *m, const char *path, const float xform[16],
                              struct sl_mesh_load_stats *st, struct sl_diag *d)
{
    return load_file(m, path, xform, st, 1, d);
}

enum sl_err sl_mesh_load_file_here(struct sl_mesh *m, const char *path, const float xform[16],
                                   struct sl_mesh_load_stats *st, struct sl_diag *d)
{
    return load_file(m, path, xform, st, 0, d);
}

enum sl_err sl_mesh_load_mem_here(struct sl_mesh *m, const void *data, size_t size, const char *name,
                                  const float xform[16], struct sl_mesh_load_stats *st, struct sl_diag *d)
{
    if (!m || !name || (!data && size))
        return sl_fail(d, SL_E_INTERNAL, name, 0, NULL, "sl_mesh_load_mem_here: NULL argument");
    if (!size || size > 0xffffffffu)
        return sl_fail(d, SL_E_SCENE, name, 0, NULL, size ? "file of %zu bytes" : "no triangles (empty file)",
                       size);
    g_ai_error[0] = '\0';
    g_ai_dropped = 0;
    struct aiLogStream ls = {.callback = ai_log, .user = NULL};
    aiAttachLogStream(&ls);
    struct sl_mesh got = {0};
    struct sl_mesh_load_stats s;
    memset(&s, 0, sizeof s);
    enum sl_err e = read_scene(&got, name, data, size, xform, &s, d);
    aiDetachAllLogStreams();
    if (!e && !mesh_append(m, &got))
        e = sl_fail(d, SL_E_NOMEM, name, 0, NULL, "out of memory appending %u triangles", got.nt);
    if (!e && st)
        *st = s;
    sl_mesh_free(&got);
    return e;
}
