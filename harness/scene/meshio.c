/*
 * meshio.c — model files into sl_mesh through assimp's C API, and welding.
 *
 * Invariants:
 * - Nothing assimp returns is trusted: every pointer is checked before use,
 *   every face index is checked against its mesh's vertex count, node mesh
 *   references against the scene's mesh count, and the node tree is walked
 *   with an explicit depth limit (no recursion a hostile file can exhaust).
 *   assimp's own post-processing only runs on a scene whose pointers, face
 *   indices and coordinates passed these checks (see sl_mesh_load_file).
 * - A file is built into a private mesh, checked and welded there, and only
 *   appended to the caller's mesh when everything succeeded, so an error
 *   leaves the caller's mesh exactly as it was (same counts, same bytes).
 * - Only vertices referenced by a triangle are copied, so points, lines and
 *   unused vertices never widen a scene's bounds.
 * - sl_mesh_weld keeps what sl_scene_from_mesh accepts: a triangle survives
 *   only if its double-precision normal has a length > 0 computed exactly as
 *   scene.c computes it, so a welded mesh never fails there for zero area.
 */
#define _DEFAULT_SOURCE   /* fork, poll, setrlimit, kill, strsignal */
#include "gen.h"
#include "meshio.h"
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include "util.h"

/* Deeper node trees than this are treated as corrupt. Real files nest a few
 * dozen levels; the limit only bounds the walk's stack. */
#define MESHIO_MAX_DEPTH 256
/* uint32 indices and counts everywhere; keep well clear of the top values,
 * which adjacency uses as markers. */
#define MESHIO_MAX_ELEMS 0x3fffffffu

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

/* ------------------------------------------------------ text pre-checks */

/*
 * assimp repairs some broken text files silently: an ASCII PLY declaring
 * more elements than it holds, OBJ face corners naming a texture coordinate
 * or normal that does not exist. These are refused here, before assimp,
 * with the line that is wrong. Only run in the reader's child.
 */
static enum sl_err ply_ascii_check(FILE *f, const char *path, struct sl_diag *d)
{
    char line[1024];
    unsigned long long declared = 0;
    int ascii = 0, lineno = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        if (!strncmp(line, "format ascii", 12))
            ascii = 1;
        else if (!strncmp(line, "element ", 8)) {
            char name[64];
            unsigned long long n;
            if (sscanf(line + 8, "%63s %llu", name, &n) == 2)
                declared += n;
        } else if (!strncmp(line, "end_header", 10))
            break;
    }
    if (!ascii)
        return SL_OK;
    unsigned long long held = 0;
    while (fgets(line, sizeof line, f)) {
        size_t k = strspn(line, " \t\r\n");
        if (line[k])
            held++;
        size_t len = strlen(line);
        while (len && line[len - 1] != '\n' && fgets(line, sizeof line, f))   /* long line */
            len = strlen(line);
    }
    if (held < declared)
        return sl_fail(d, SL_E_SCENE, path, 0, NULL, "truncated file: the header declares %llu "
                       "element lines, the file holds %llu", declared, held);
    return SL_OK;
}

/* v/vt/vn counts and, per face corner, indices in 1..count (or negative,
 * relative to the count so far). */
static enum sl_err obj_check(FILE *f, const char *path, struct sl_diag *d)
{
    char line[4096];
    long long cnt[3] = {0, 0, 0}, maxref[3] = {0, 0, 0};
    int maxline[3] = {0, 0, 0}, lineno = 0;
    static const char *what[3] = {"vertex", "texture coordinate", "normal"};
    while (fgets(line, sizeof line, f)) {
        lineno++;
        if (line[0] == 'v' && line[1] == ' ')
            cnt[0]++;
        else if (line[0] == 'v' && line[1] == 't' && (line[2] == ' ' || line[2] == '\t'))
            cnt[1]++;
        else if (line[0] == 'v' && line[1] == 'n' && (line[2] == ' ' || line[2] == '\t'))
            cnt[2]++;
        else if (line[0] == 'f' && (line[1] == ' ' || line[1] == '\t')) {
            char *q = line + 2;
            for (;;) {
                while (*q == ' ' || *q == '\t')
                    q++;
                if (!*q || *q == '\n' || *q == '\r' || *q == '#')
                    break;
                for (int k = 0; k < 3; k++) {
                    char *e;
                    if (*q == '/' || *q == ' ' || *q == '\t' || *q == '\n' || *q == '\r' || !*q) {
                        if (*q == '/')
                            q++;
                        continue;   /* absent */
                    }
                    long long v = strtoll(q, &e, 10);
                    if (e == q)
                        return sl_fail(d, SL_E_SCENE, path, lineno, NULL, "corrupt file: "
                                       "bad face corner (line %d)", lineno);
                    q = e;
                    if (v < 0 ? -v > cnt[k] : v == 0)
                        return sl_fail(d, SL_E_SCENE, path, lineno, NULL, "corrupt file: line %d: "
                                       "face names %s %lld of %lld", lineno, what[k], v, cnt[k]);
                    if (v > maxref[k]) {
                        maxref[k] = v;
                        maxline[k] = lineno;
                    }
                    if (*q == '/')
                        q++;
                    else
                        break;
                }
                while (*q && *q != ' ' && *q != '\t' && *q != '\n' && *q != '\r')
                    q++;
            }
        }
        size_t len = strlen(line);
        while (len && line[len - 1] != '\n' && fgets(line, sizeof line, f))
            len = strlen(line);
    }
    for (int k = 0; k < 3; k++)
        if (maxref[k] > cnt[k])
            return sl_fail(d, SL_E_SCENE, path, maxline[k], NULL, "corrupt file: line %d: face "
                           "names %s %lld of %lld", maxline[k], what[k], maxref[k], cnt[k]);
    return SL_OK;
}

static enum sl_err text_precheck(const char *path, struct sl_diag *d)
{
    const char *dot = strrchr(path, '.');
    if (!dot)
        return SL_OK;
    int ply = !strcasecmp(dot, ".ply"), obj = !strcasecmp(dot, ".obj");
    if (!ply && !obj)
        return SL_OK;
    FILE *f = fopen(path, "rb");
    if (!f)
        return SL_OK;   /* load_direct reports it */
    enum sl_err e = ply ? ply_ascii_check(f, path, d) : obj_check(f, path, d);
    fclose(f);
    return e;
}

/* assimp logs some errors and carries on with a repaired scene (an OFF face
 * index out of range); the first error logged about an index or a range
 * makes the file fail. Other logged errors (a missing material) are about
 * things we never read. */
static char g_ai_error[256];

static void ai_log(const char *msg, char *user)
{
    (void)user;
    if (g_ai_error[0] || strncmp(msg, "Error", 5) != 0 ||
        !(strstr(msg, "ndex") || strstr(msg, "range")))
        return;
    const char *m = strstr(msg, ": ");
    snprintf(g_ai_error, sizeof g_ai_error, "%s", m ? m + 2 : msg);
    size_t n = strlen(g_ai_error);
    while (n && (g_ai_error[n - 1] == '\n' || g_ai_error[n - 1] == '\r'))
        g_ai_error[--n] = 0;
}

/* In the reader's process: assimp reads the file, its result is checked and
 * welded into m. sl_mesh_load_file runs this in a child (meshjail). */
static enum sl_err load_direct(struct sl_mesh *m, const char *path, const float xform[16],
                               struct sl_mesh_load_stats *st, struct sl_diag *d)
{
    if (!m || !path)
        return sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "sl_mesh_load_file: NULL argument");
    /* Opened here first so a missing or unreadable file gets the system's
     * reason rather than a format guess, and an empty one says so. */
    FILE *f = fopen(path, "rb");
    if (!f)
        return sl_fail(d, SL_E_SCENE, path, 0, NULL, "cannot open: %s", strerror(errno));
    unsigned char c0;
    size_t got = fread(&c0, 1, 1, f);
    int rerr = ferror(f) ? errno : 0;
    fclose(f);
    if (rerr)
        return sl_fail(d, SL_E_SCENE, path, 0, NULL, "cannot read: %s", strerror(rerr));
    if (got == 0)
        return sl_fail(d, SL_E_SCENE, path, 0, NULL, "no triangles (empty file)");

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
    enum sl_err e = text_precheck(path, d);
    if (e)
        return e;
    struct aiLogStream ls = {.callback = ai_log, .user = NULL};
    aiAttachLogStream(&ls);
    const struct aiScene *sc = aiImportFile(path, 0);
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

/* ------------------------------------------------------------- the jail */

/*
 * Model files are untrusted and assimp is not hardened: malformed files
 * crash it (SIGSEGV) or loop forever. So the reading runs in a forked child
 * that does only assimp + our checks + writing the result into a pipe, then
 * _exit()s; it inherits no duty to flush or clean anything. The child is
 * limited in CPU time (RLIMIT_CPU), address space (RLIMIT_AS) and wall
 * time (the parent kills it), all scaled by the file's size; it writes no
 * core file. The parent checks what comes back (counts, index ranges,
 * finite coordinates) before it appends anything to m, so a child that went
 * wrong cannot hand over a broken mesh.
 */
#define JAIL_CPU_BASE_S   3     /* CPU seconds for any file ... */
#define JAIL_CPU_PER_MB_S 1     /* ... plus this per MiB of file */
#define JAIL_AS_BASE      (4ull << 30)  /* address space beyond the parent's ... */
#define JAIL_AS_PER_BYTE  64ull         /* ... plus this per byte of file */

struct jail_head {
    uint32_t                  magic;
    int32_t                   err;
    struct sl_diag            d;
    struct sl_mesh_load_stats st;
    uint32_t                  nv, nt;
};
#define JAIL_MAGIC 0x534c4d31u   /* "SLM1" */

static int write_all(int fd, const void *p, size_t n)
{
    const char *c = p;
    while (n) {
        ssize_t w = write(fd, c, n > (1u << 20) ? (1u << 20) : n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return 0;
        c += w;
        n -= (size_t)w;
    }
    return 1;
}

static unsigned long long vm_size(void)
{
    unsigned long long pages = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f) {
        if (fscanf(f, "%llu", &pages) != 1)
            pages = 0;
        fclose(f);
    }
    long ps = sysconf(_SC_PAGESIZE);
    return pages * (unsigned long long)(ps > 0 ? ps : 4096);
}

static void jail_child(int fd, const char *path, const float xform[16], unsigned cpu_s,
                       unsigned long long as_bytes)
{
    struct rlimit r = {.rlim_cur = cpu_s, .rlim_max = cpu_s + 1};
    setrlimit(RLIMIT_CPU, &r);
    r.rlim_cur = r.rlim_max = as_bytes;
    setrlimit(RLIMIT_AS, &r);
    r.rlim_cur = r.rlim_max = 0;
    setrlimit(RLIMIT_CORE, &r);
    int null = open("/dev/null", O_RDWR);
    if (null >= 0) {   /* assimp may print; only main() speaks */
        dup2(null, 1);
        dup2(null, 2);
    }
    struct sl_mesh m = {0};
    struct jail_head h;
    memset(&h, 0, sizeof h);
    h.magic = JAIL_MAGIC;
    h.err = (int32_t)load_direct(&m, path, xform, &h.st, &h.d);
    if (!h.err) {
        h.nv = m.nv;
        h.nt = m.nt;
    }
    int ok = write_all(fd, &h, sizeof h);
    if (ok && !h.err)
        ok = write_all(fd, m.pos, (size_t)m.nv * 3 * sizeof(float)) &&
             write_all(fd, m.idx, (size_t)m.nt * 3 * sizeof(uint32_t));
    _exit(ok ? 0 : 3);
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Read n bytes before the deadline: 1 done, 0 end of data, -1 timeout, -2 error. */
static int read_until(int fd, void *p, size_t n, double deadline)
{
    char *c = p;
    while (n) {
        double left = deadline - now_s();
        if (left <= 0)
            return -1;
        struct pollfd pf = {.fd = fd, .events = POLLIN};
        int k = poll(&pf, 1, (int)(left * 1000.0) + 1);
        if (k < 0 && errno == EINTR)
            continue;
        if (k < 0)
            return -2;
        if (k == 0)
            continue;
        ssize_t r = read(fd, c, n);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0)
            return -2;
        if (r == 0)
            return 0;
        c += r;
        n -= (size_t)r;
    }
    return 1;
}

static const char *sig_name(int s)
{
    switch (s) {
    case SIGSEGV: return "SIGSEGV";
    case SIGBUS:  return "SIGBUS";
    case SIGABRT: return "SIGABRT";
    case SIGFPE:  return "SIGFPE";
    case SIGILL:  return "SIGILL";
    case SIGKILL: return "SIGKILL";
    case SIGXCPU: return "SIGXCPU";
    default:      return "signal";
    }
}

/* What the child's end says, once its data did not come back whole. */
static enum sl_err jail_verdict(int status, int timed_out, unsigned cpu_s, unsigned wall_s,
                                unsigned long long as_mb, const char *path, struct sl_diag *d)
{
    const char *pre = "cannot read the model";
    if (timed_out)
        return sl_fail(d, SL_E_SCENE, path, 0, NULL,
                       "%s: the reader was stopped after %u s (wall clock): a hang or a file "
                       "too large", pre, wall_s);
    if (WIFSIGNALED(status)) {
        int s = WTERMSIG(status);
        if (s == SIGXCPU || s == SIGKILL)
            return sl_fail(d, SL_E_SCENE, path, 0, NULL,
                           "%s: the reader was stopped after %u s of CPU (%s): a hang or a "
                           "file too large", pre, cpu_s, sig_name(s));
        return sl_fail(d, SL_E_SCENE, path, 0, NULL,
                       "%s: the reader crashed (signal %d, %s; memory limit %llu MiB)", pre, s,
                       sig_name(s), as_mb);
    }
    return sl_fail(d, SL_E_SCENE, path, 0, NULL, "%s: the reader ended without a result "
                   "(exit %d)", pre, WIFEXITED(status) ? WEXITSTATUS(status) : -1);
}

enum sl_err sl_mesh_load_file(struct sl_mesh *m, const char *path, const float xform[16],
                              struct sl_mesh_load_stats *st, struct sl_diag *d)
{
    if (!m || !path)
        return sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "sl_mesh_load_file: NULL argument");
    struct stat sb;
    unsigned long long size = stat(path, &sb) == 0 ? (unsigned long long)sb.st_size : 0;
    unsigned cpu_s = JAIL_CPU_BASE_S + JAIL_CPU_PER_MB_S * (unsigned)(size >> 20);
    unsigned wall_s = 2 * cpu_s + 5;   /* a loaded machine gives the child less than a core */
    unsigned long long as = vm_size() + JAIL_AS_BASE + JAIL_AS_PER_BYTE * size;
    int fds[2];
    if (pipe(fds) != 0)
        return sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "cannot read the model: pipe: %s",
                       strerror(errno));
    fflush(NULL);   /* the child must not write the parent's buffers again */
    pid_t pid = fork();
    if (pid < 0) {
        int en = errno;
        close(fds[0]);
        close(fds[1]);
        return sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "cannot read the model: fork: %s",
                       strerror(en));
    }
    if (pid == 0) {
        close(fds[0]);
        jail_child(fds[1], path, xform, cpu_s, as);
    }
    close(fds[1]);
    double deadline = now_s() + wall_s;
    struct jail_head h;
    struct sl_mesh got = {0};
    int r = read_until(fds[0], &h, sizeof h, deadline), bad = 0;
    enum sl_err e = SL_OK;
    if (r == 1 && h.magic != JAIL_MAGIC)
        bad = 1;
    else if (r == 1 && h.err) {
        if (h.err < 0 || h.err >= SL_ERR_COUNT)
            bad = 1;
        else {
            h.d.file[sizeof h.d.file - 1] = h.d.key[sizeof h.d.key - 1] = 0;
            h.d.msg[sizeof h.d.msg - 1] = 0;
            if (d)
                *d = h.d;
            e = (enum sl_err)h.err;
        }
    } else if (r == 1) {
        if (h.nv == 0 || h.nt == 0 || h.nv > MESHIO_MAX_ELEMS || h.nt > MESHIO_MAX_ELEMS)
            bad = 1;
        else {
            got.pos = malloc((size_t)h.nv * 3 * sizeof(float));
            got.idx = malloc((size_t)h.nt * 3 * sizeof(uint32_t));
            if (!got.pos || !got.idx)
                e = sl_fail(d, SL_E_NOMEM, path, 0, NULL, "mesh of %u triangles", h.nt);
            else {
                got.nv = got.cap_v = h.nv;
                got.nt = got.cap_t = h.nt;
                r = read_until(fds[0], got.pos, (size_t)h.nv * 3 * sizeof(float), deadline);
                if (r == 1)
                    r = read_until(fds[0], got.idx, (size_t)h.nt * 3 * sizeof(uint32_t), deadline);
            }
        }
    }
    if (r == -1)
        kill(pid, SIGKILL);
    close(fds[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    if (!e && r != 1)
        e = jail_verdict(status, r == -1, cpu_s, wall_s, as >> 20, path, d);
    else if (!e && bad)
        e = sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "cannot read the model: the reader "
                    "handed back a malformed result");
    /* the child's result is checked like assimp's was */
    for (size_t i = 0; !e && got.pos && i < 3 * (size_t)got.nv; i++)
        if (!isfinite(got.pos[i]))
            e = sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "cannot read the model: the reader "
                        "handed back a non-finite vertex");
    for (size_t i = 0; !e && got.idx && i < 3 * (size_t)got.nt; i++)
        if (got.idx[i] >= got.nv)
            e = sl_fail(d, SL_E_INTERNAL, path, 0, NULL, "cannot read the model: the reader "
                        "handed back an index out of range");
    if (!e && !mesh_append(m, &got))
        e = sl_fail(d, SL_E_NOMEM, path, 0, NULL, "out of memory appending %u triangles", got.nt);
    if (!e && st)
        *st = h.st;
    sl_mesh_free(&got);
    return e;
}
