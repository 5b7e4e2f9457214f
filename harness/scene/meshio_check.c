/*
 * meshio_check.c — checks of a model file's own bytes before assimp reads
 * it: what assimp would silently repair or misread (issue 15).
 *
 * Invariants:
 * - Every check is bounded by the file's size: each loop step consumes at
 *   least one byte or one line, and declared counts are only compared with
 *   what is present, never used to allocate or to loop, so a header claiming
 *   billions of elements costs nothing.
 * - A file is refused only for a defect we can name (declared vs present
 *   counts, an index out of range) with the file, the line or element, and
 *   the numbers; anything these checks do not understand (an unknown
 *   property type, a header without end_header) passes unchanged to assimp,
 *   which runs in the reader's child with limits (meshio_child.c).
 * - Checks only read; they run in the reader's child, like assimp.
 */
#define _DEFAULT_SOURCE
#include "meshio_check.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

/* ------------------------------------------------------------------ PLY */

/*
 * assimp repairs or misreads broken PLY silently: an ASCII file declaring
 * more elements than it holds loads with made-up triangles, and a binary one
 * cut short is read past its end (garbage indices, or a crash). So the
 * header is parsed here and the data measured against it: ASCII counts
 * element lines; binary walks the elements (fixed-size rows by arithmetic,
 * rows with lists item by item) and checks every face's vertex indices
 * against the declared vertex count.
 */
#define PLY_MAX_ELEMS 32
#define PLY_MAX_PROPS 64

enum ply_fmt { PLY_UNKNOWN, PLY_ASCII, PLY_LE, PLY_BE };

struct ply_prop {
    int list;           /* a list: count of count_size bytes, then items */
    int count_size;
    int size;           /* scalar (or list item) size in bytes */
    int is_signed, is_float;
    int is_index;       /* face vertex_indices / vertex_index */
};

struct ply_elem {
    char name[64];
    unsigned long long n;
    int nprops;
    int row;            /* bytes per row when no property is a list, else -1 */
    struct ply_prop props[PLY_MAX_PROPS];
};

struct ply_head {
    enum ply_fmt fmt;
    int nelems;
    struct ply_elem el[PLY_MAX_ELEMS];
    unsigned long long nvert;   /* the 'vertex' element's count */
    long data;                  /* offset of the first data byte */
    char why[160];              /* ply_header -1: what is wrong with the header */
};

/* 1 with size and kind set, 0 for a type name we do not know. */
static int ply_type(const char *t, int *size, int *sgn, int *flt)
{
    static const struct { const char *name; int size, sgn, flt; } ty[] = {
        {"char", 1, 1, 0},   {"int8", 1, 1, 0},    {"uchar", 1, 0, 0},  {"uint8", 1, 0, 0},
        {"short", 2, 1, 0},  {"int16", 2, 1, 0},   {"ushort", 2, 0, 0}, {"uint16", 2, 0, 0},
        {"int", 4, 1, 0},    {"int32", 4, 1, 0},   {"uint", 4, 0, 0},   {"uint32", 4, 0, 0},
        {"float", 4, 1, 1},  {"float32", 4, 1, 1}, {"double", 8, 1, 1}, {"float64", 8, 1, 1},
    };
    for (size_t i = 0; i < sizeof ty / sizeof ty[0]; i++)
        if (!strcmp(t, ty[i].name)) {
            *size = ty[i].size;
            *sgn = ty[i].sgn;
            *flt = ty[i].flt;
            return 1;
        }
    return 0;
}

/* 1: header read whole and understood; 0: leave the file to assimp; -1: a
 * header no PLY reader can take (h->why), refused here. assimp's PLY reader
 * crashes or reads past the end on such headers (an unknown format word,
 * NUL bytes, no end_header, a property before any element, a property type
 * it skips: its binary rows then have another size than the file's), so
 * these are refused whether or not the rest is understood: the header is
 * scanned to its end_header in any case. Limits of ours (elements,
 * properties, a line of 1 KiB) only stop the understanding (0). */
static int ply_header(FILE *f, struct ply_head *h)
{
    char line[1024];
    memset(h, 0, sizeof *h);
    struct ply_elem *cur = NULL;
    long at = ftell(f);
    int lineno = 0, opaque = 0, cont = 0;   /* cont: this piece continues a long line */
    while (fgets(line, sizeof line, f)) {
        size_t len = strlen(line);
        long next = ftell(f);
        if (at >= 0 && next >= 0 && (long)len < next - at) {
            snprintf(h->why, sizeof h->why, "a NUL byte in the header (at byte %ld)", at + (long)len);
            return -1;
        }
        at = next;
        int piece = cont;
        lineno += !cont;
        cont = !len || line[len - 1] != '\n';
        if (cont && feof(f))
            break;   /* the last line, without end_header */
        if (piece)
            continue;
        if (cont)
            opaque = 1;   /* a header line of 1 KiB: not ours to judge */
        char a[64], b[64], c[64], e[64];
        /* a token, as assimp reads it: "end_header\x0e..." is not one, and
         * assimp's ASCII reader then takes the body for header lines
         * (25 s and more on a 2 KiB file) */
        if (!strncmp(line, "end_header", 10) && strchr(" \t\r\n", line[10])) {
            if (opaque)
                return 0;
            for (int i = 0; i < h->nelems; i++) {
                struct ply_elem *el = &h->el[i];
                el->row = 0;
                for (int k = 0; k < el->nprops && el->row >= 0; k++)
                    el->row = el->props[k].list ? -1 : el->row + el->props[k].size;
            }
            if (h->fmt == PLY_UNKNOWN) {
                snprintf(h->why, sizeof h->why, "no format line before end_header");
                return -1;
            }
            h->data = ftell(f);
            return h->data > 0;
        }
        if (opaque)
            continue;
        if (!strncmp(line, "format ", 7)) {
            if (sscanf(line + 7, "%63s", a) != 1)
                a[0] = '\0';   /* refused below, as no format */
            h->fmt = !strcmp(a, "ascii") ? PLY_ASCII : !strcmp(a, "binary_little_endian") ? PLY_LE
                     : !strcmp(a, "binary_big_endian") ? PLY_BE : PLY_UNKNOWN;
            if (h->fmt == PLY_UNKNOWN) {
                snprintf(h->why, sizeof h->why, "format '%.63s' is none of ascii, binary_little_endian, "
                         "binary_big_endian", a);
                return -1;
            }
        } else if (!strncmp(line, "element ", 8)) {
            unsigned long long n;
            if (sscanf(line + 8, "%63s %llu", a, &n) != 2) {
                snprintf(h->why, sizeof h->why, "line %d: an element without a name and a count", lineno);
                return -1;
            }
            if (h->nelems >= PLY_MAX_ELEMS) {
                opaque = 1;
                continue;
            }
            cur = &h->el[h->nelems++];
            snprintf(cur->name, sizeof cur->name, "%s", a);
            cur->n = n;
            if (!strcmp(a, "vertex"))
                h->nvert = n;
        } else if (!strncmp(line, "property ", 9)) {
            if (!cur) {
                snprintf(h->why, sizeof h->why, "line %d: a property before any element", lineno);
                return -1;
            }
            if (cur->nprops >= PLY_MAX_PROPS) {
                opaque = 1;
                continue;
            }
            struct ply_prop *p = &cur->props[cur->nprops++];
            int s = 0, g, fl;
            const char *bad = NULL;
            if (sscanf(line + 9, "list %63s %63s %63s", a, b, c) == 3) {
                if (!ply_type(a, &p->count_size, &g, &fl) || fl)
                    bad = a;
                else if (!ply_type(b, &p->size, &p->is_signed, &p->is_float))
                    bad = b;
                p->list = 1;
                p->is_index = !strcmp(cur->name, "face") &&
                              (!strcmp(c, "vertex_indices") || !strcmp(c, "vertex_index"));
            } else if (sscanf(line + 9, "%63s %63s", a, e) == 2 && strcmp(a, "list")) {
                if (!ply_type(a, &s, &g, &fl))
                    bad = a;
                p->size = s;
            } else {
                snprintf(h->why, sizeof h->why, "line %d: a property without a type and a name", lineno);
                return -1;
            }
            if (bad) {
                snprintf(h->why, sizeof h->why, "line %d: property type '%.40s' is not a PLY type%s", lineno,
                         bad, p->list && bad == a ? " for a list's count" : "");
                return -1;
            }
        }
    }
    if (feof(f) || cont) {
        snprintf(h->why, sizeof h->why, "the header has no end_header line");
        return -1;
    }
    return 0;
}

static enum sl_err ply_ascii_check(FILE *f, const struct ply_head *h, const char *path,
                                   struct sl_diag *d)
{
    char line[1024];
    unsigned long long declared = 0, held = 0;
    for (int i = 0; i < h->nelems; i++)
        declared += h->el[i].n;
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

/* An integer of `size` bytes in the file's byte order. */
static long long ply_int(const unsigned char *b, int size, int sgn, int big)
{
    unsigned long long u = 0;
    for (int i = 0; i < size; i++)
        u |= (unsigned long long)b[big ? size - 1 - i : i] << (8 * i);
    if (sgn && size < 8 && (u >> (8 * size - 1)) & 1)
        return (long long)u - (1ll << (8 * size));
    return (long long)u;
}

static enum sl_err ply_binary_check(FILE *f, const struct ply_head *h, unsigned long long size,
                                    const char *path, struct sl_diag *d)
{
    const int big = h->fmt == PLY_BE;
    unsigned long long pos = (unsigned long long)h->data;
    for (int i = 0; i < h->nelems; i++) {
        const struct ply_elem *el = &h->el[i];
        if (el->row >= 0) {   /* fixed rows: arithmetic, no reading */
            unsigned long long left = size - pos;
            if (el->row && el->n > left / (unsigned)el->row)
                return sl_fail(d, SL_E_SCENE, path, 0, NULL, "truncated file: the header declares "
                               "%llu '%s' elements (%d bytes each), the file holds %llu",
                               el->n, el->name, el->row, left / (unsigned)el->row);
            pos += el->n * (unsigned)el->row;
            continue;
        }
        if (fseek(f, (long)pos, SEEK_SET) != 0)
            return SL_OK;   /* not seekable: leave it to assimp */
        for (unsigned long long r = 0; r < el->n; r++) {
            for (int k = 0; k < el->nprops; k++) {
                const struct ply_prop *p = &el->props[k];
                unsigned char b[8];
                int need = p->list ? p->count_size : p->size;
                if (size - pos < (unsigned)need || fread(b, 1, (size_t)need, f) != (size_t)need)
                    goto cut;
                pos += (unsigned)need;
                if (!p->list)
                    continue;
                /* read as unsigned whatever its type: a negative count is
                 * then a huge one, refused as truncation below */
                long long cnt = ply_int(b, p->count_size, 0, big);
                unsigned long long bytes = (unsigned long long)cnt * (unsigned)p->size;
                if (size - pos < bytes)
                    goto cut;
                if (!p->is_index || p->is_float) {
                    pos += bytes;
                    if (fseek(f, (long)pos, SEEK_SET) != 0)
                        return SL_OK;
                    continue;
                }
                for (long long c = 0; c < cnt; c++) {
                    if (fread(b, 1, (size_t)p->size, f) != (size_t)p->size)
                        goto cut;
                    long long v = ply_int(b, p->size, p->is_signed, big);
                    if (v < 0 || (unsigned long long)v >= h->nvert)
                        return sl_fail(d, SL_E_SCENE, path, 0, NULL, "corrupt file: face %llu "
                                       "names vertex %lld, the header declares %llu vertices",
                                       r, v, h->nvert);
                }
                pos += bytes;
            }
            continue;
        cut:
            return sl_fail(d, SL_E_SCENE, path, 0, NULL, "truncated file: the header declares "
                           "%llu '%s' elements, the data ends in element %llu", el->n, el->name, r);
        }
    }
    return SL_OK;
}

static enum sl_err ply_check(FILE *f, unsigned long long size, const char *path, struct sl_diag *d)
{
    struct ply_head *h = malloc(sizeof *h);
    if (!h)
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "PLY header");
    enum sl_err e = SL_OK;
    char magic[5] = "";
    /* assimp's PLY reader takes a .ply file whose first line starts with
     * 'ply' in any case ("plyy" too): all of those are checked */
    int is_ply = fread(magic, 1, 3, f) == 3 && !strncasecmp(magic, "ply", 3);
    rewind(f);
    int got = ply_header(f, h);
    if (got < 0 && !is_ply)
        got = 0;   /* not a PLY file at all: assimp says what it is */
    if (got < 0)
        e = sl_fail(d, SL_E_SCENE, path, 0, NULL, "corrupt PLY header: %s", h->why);
    else if (got) {
        if (h->fmt == PLY_ASCII)
            e = ply_ascii_check(f, h, path, d);
        else if (size >= (unsigned long long)h->data)
            e = ply_binary_check(f, h, size, path, d);
    }
    free(h);
    return e;
}

/* ------------------------------------------------------------------ OBJ */

/*
 * assimp repairs OBJ face corners naming a texture coordinate or normal
 * that does not exist. They are refused here with the line that is wrong.
 */
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

/* ----------------------------------------------------------------- glTF */

/*
 * assimp 5.2's glTF 2 reader dereferences a skin's inverseBindMatrices
 * without looking (a NULL read: the reader crashes) when a skinned node's
 * skin has none, which glTF 2.0 allows (identity matrices). We read no
 * skin, but assimp cannot be told to skip them, so such a file is refused
 * naming the skin. The JSON is only scanned (strings, nesting, the keys of
 * each top-level "skins" entry); a text this scan does not follow (nested
 * past its stack, or cut) passes to assimp unchanged.
 */
#define GLTF_MAX_DEPTH 64

static enum sl_err gltf_check(FILE *f, const char *path, struct sl_diag *d)
{
    char key[32] = "";           /* the last key read, truncated */
    int depth = 0, line = 1, in_skins = 0, skin = -1, has_ibm = 0, skin_line = 0;
    unsigned char is_obj[GLTF_MAX_DEPTH + 1], want_key[GLTF_MAX_DEPTH + 1];
    int c;
    while ((c = getc(f)) != EOF) {
        if (c == '\n')
            line++;
        else if (c == '"') {
            size_t n = 0;
            int esc = 0;
            char buf[32];
            while ((c = getc(f)) != EOF && (esc || c != '"')) {
                esc = !esc && c == '\\';
                if (c == '\n')
                    line++;
                if (n + 1 < sizeof buf)
                    buf[n++] = (char)c;
            }
            if (c == EOF)
                return SL_OK;
            buf[n] = '\0';
            if (depth && is_obj[depth] && want_key[depth]) {
                snprintf(key, sizeof key, "%s", buf);
                want_key[depth] = 0;
                if (depth == 3 && in_skins && !strcmp(buf, "inverseBindMatrices"))
                    has_ibm = 1;
            }
        } else if (c == '{' || c == '[') {
            if (depth == GLTF_MAX_DEPTH)
                return SL_OK;
            depth++;
            is_obj[depth] = c == '{';
            want_key[depth] = c == '{';
            if (depth == 2 && c == '[' && !strcmp(key, "skins"))
                in_skins = 1;
            if (depth == 3 && in_skins && c == '{') {
                skin++;
                has_ibm = 0;
                skin_line = line;
            }
        } else if (c == '}' || c == ']') {
            if (depth == 3 && in_skins && c == '}' && !has_ibm)
                return sl_fail(d, SL_E_SCENE, path, skin_line, NULL, "skin %d (line %d) has no "
                               "inverseBindMatrices: assimp's glTF reader crashes on such a skin (add "
                               "the matrices, or remove the skin: shadowlab does not read skins)",
                               skin, skin_line);
            if (depth == 2)
                in_skins = 0;
            if (depth)
                depth--;
        } else if (c == ',' && depth && is_obj[depth]) {
            want_key[depth] = 1;
        }
    }
    return SL_OK;
}

/* 'p' (PLY), 'o' (OBJ), 'g' (glTF JSON) or 0 (not checked), by the name's
 * extension */
static int check_kind(const char *name)
{
    const char *dot = strrchr(name, '.');
    return !dot ? 0 : !strcasecmp(dot, ".ply") ? 'p' : !strcasecmp(dot, ".obj") ? 'o'
                    : !strcasecmp(dot, ".gltf") ? 'g' : 0;
}

static enum sl_err check_stream(FILE *f, int kind, unsigned long long size, const char *name,
                                struct sl_diag *d)
{
    return kind == 'p' ? ply_check(f, size, name, d) : kind == 'o' ? obj_check(f, name, d)
                                                                   : gltf_check(f, name, d);
}

enum sl_err sl_mesh_precheck(const char *path, struct sl_diag *d)
{
    int kind = check_kind(path);
    if (!kind)
        return SL_OK;
    FILE *f = fopen(path, "rb");
    if (!f)
        return SL_OK;   /* the reader reports it */
    struct stat sb;
    enum sl_err e = fstat(fileno(f), &sb) == 0 ? check_stream(f, kind, (unsigned long long)sb.st_size, path, d)
                                               : SL_OK;
    fclose(f);
    return e;
}

enum sl_err sl_mesh_precheck_mem(const void *data, size_t size, const char *name, struct sl_diag *d)
{
    int kind = check_kind(name);
    if (!kind || !size)
        return SL_OK;
    FILE *f = fmemopen((void *)data, size, "rb");
    if (!f)
        return SL_OK;
    enum sl_err e = check_stream(f, kind, size, name, d);
    fclose(f);
    return e;
}
