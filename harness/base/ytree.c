/*
 * ytree.c — see ytree.h.
 * Invariants: the file is opened and read once; its bytes go through one
 * libyaml parse and are freed before sl_ytree_read returns; every node
 * lives in the tree's arena (a grafted -D value too, and whatever it
 * replaced), so sl_ytree_free frees all; an open container's depth never
 * passes SL_YAML_MAX_DEPTH, so every walk of the tree (paths, binding,
 * freeing) recurses at most that deep plus a -D path's steps.
 */
#define _POSIX_C_SOURCE 200809L
#include "ytree.h"
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <yaml.h>
#include "util.h"

#define SRC_MAX 255   /* the file and up to 254 -D values (origin is a byte) */

struct chunk { struct chunk *next; unsigned used; struct sl_ynode node[1024]; };
/* scalars' texts, packed: a malloc each would double a small scalar's cost */
struct tchunk { struct tchunk *next; size_t used, cap; char buf[]; };

struct sl_yaml_pos {
    struct sl_ynode *root;
    char            *src[SRC_MAX + 1];   /* src[0] the file, src[k] "-D KEY=VALUE" */
    int              nsrc;
    unsigned long long hash;
    struct chunk    *chunks;
    struct tchunk   *texts;
    size_t           nodes, max_nodes;
};

/* ---- the arena ---- */

static struct sl_ynode *node_new(struct sl_yaml_pos *t, int kind, int line, int col, int origin)
{
    if (t->nodes >= t->max_nodes)
        return NULL;
    if (!t->chunks || t->chunks->used == sizeof t->chunks->node / sizeof t->chunks->node[0]) {
        struct chunk *c = malloc(sizeof *c);
        if (!c)
            return NULL;
        c->next = t->chunks;
        c->used = 0;
        t->chunks = c;
    }
    struct sl_ynode *n = &t->chunks->node[t->chunks->used++];
    memset(n, 0, sizeof *n);
    n->kind = (unsigned char)kind;
    n->line = line;
    n->col = col;
    n->origin = (unsigned char)origin;
    t->nodes++;
    return n;
}

/* A copy of s[0..len) (NUL added) in the text arena. */
static char *text_new(struct sl_yaml_pos *t, const char *s, size_t len)
{
    struct tchunk *c = t->texts;
    if (!c || c->cap - c->used < len + 1) {
        size_t cap = len + 1 > 65536 ? len + 1 : 65536;
        if (!(c = malloc(sizeof *c + cap)))
            return NULL;
        c->used = 0;
        c->cap = cap;
        if (t->texts && len + 1 > 65536) {   /* a big one: behind the open chunk, which stays open */
            c->next = t->texts->next;
            t->texts->next = c;
        } else {
            c->next = t->texts;
            t->texts = c;
        }
    }
    char *p = c->buf + c->used;
    memcpy(p, s, len);
    p[len] = '\0';
    c->used += len + 1;
    return p;
}

static int slot_push(struct sl_ynode *p, unsigned used, struct sl_ynode *k)
{
    if (used == p->cap) {
        unsigned cap = p->cap ? 2 * p->cap : 4;
        void *q = realloc(p->kid, (size_t)cap * sizeof *p->kid);
        if (!q)
            return 0;
        p->kid = q;
        p->cap = cap;
    }
    p->kid[used] = k;
    return 1;
}

void sl_ytree_free(struct sl_yaml_pos *t)
{
    if (!t)
        return;
    for (struct chunk *c = t->chunks, *next; c; c = next) {
        next = c->next;
        for (unsigned i = 0; i < c->used; i++)
            free(c->node[i].kid);
        free(c);
    }
    for (struct tchunk *c = t->texts, *next; c; c = next) {
        next = c->next;
        free(c);
    }
    for (int i = 0; i < t->nsrc; i++)
        free(t->src[i]);
    free(t);
}

/* ---- reading ---- */

/* Read the whole file, refusing it before reading when it is over
 * max_bytes (the caller's limit for its kind of file). */
static enum sl_err read_text(const char *path, size_t max_bytes, unsigned char **text, size_t *len,
                             enum sl_err kind, struct sl_diag *d)
{
    *text = NULL;
    *len = 0;
    int fd;
    long long size;
    enum sl_err e = sl_open_regular(path, &fd, &size, d);   /* no FIFO, device or folder */
    if (e)
        return e;
    if ((unsigned long long)size > (unsigned long long)max_bytes) {
        close(fd);
        char limit[32];
        return sl_fail(d, kind, path, 0, NULL, "file of %lld bytes: at most %s are read for this kind of file",
                       size, sl_size_text(max_bytes, limit, sizeof limit));
    }
    /* +1 so a file that grew since fstat is seen as over the limit; the
     * reads stop there whatever the file does */
    size_t cap = (size_t)size + 1;
    unsigned char *buf = malloc(cap);
    if (!buf) {
        close(fd);
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "reading the file");
    }
    size_t n = 0;
    int err = 0;
    while (n < cap) {
        ssize_t k = read(fd, buf + n, cap - n);
        if (k < 0 && errno == EINTR)
            continue;
        if (k < 0)
            err = errno;
        if (k <= 0)
            break;
        n += (size_t)k;
    }
    close(fd);
    if (err) {
        free(buf);
        return sl_fail(d, SL_E_IO, path, 0, NULL, "cannot read: %s", strerror(err));
    }
    if (n > (size_t)size) {
        free(buf);
        return sl_fail(d, kind, path, 0, NULL, "the file grew while being read");
    }
    *text = buf;
    *len = n;
    return SL_OK;
}

/* libyaml refuses bytes that are not UTF-8 text and control characters
 * without saying where; find the first such byte and name its line. */
static enum sl_err check_text(const char *path, const unsigned char *s, size_t n, enum sl_err kind,
                              struct sl_diag *d)
{
    int line = 1;
    size_t col0 = 0;
    for (size_t i = 0; i < n;) {
        unsigned c = s[i];
        if (c == '\n') {
            line++;
            col0 = ++i;
            continue;
        }
        if (c < 0x80) {
            if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7f)
                return sl_fail(d, kind, path, line, NULL, "%s (byte 0x%02x at column %zu): not YAML text",
                               c == 0 ? "NUL byte" : "control character", c, i - col0 + 1);
            i++;
            continue;
        }
        /* a UTF-8 sequence: lead byte, then 1..3 continuation bytes;
         * overlong forms and surrogates are refused as libyaml does */
        size_t k = c >= 0xc2 && c <= 0xdf ? 1 : c >= 0xe0 && c <= 0xef ? 2 : c >= 0xf0 && c <= 0xf4 ? 3 : 0;
        int ok = k > 0 && i + k < n;
        uint32_t cp = k == 1 ? c & 0x1f : k == 2 ? c & 0x0f : c & 0x07;
        for (size_t j = 1; ok && j <= k; j++) {
            if ((s[i + j] & 0xc0) != 0x80)
                ok = 0;
            cp = (cp << 6) | (s[i + j] & 0x3f);
        }
        if (ok && ((k == 2 && (cp < 0x800 || (cp >= 0xd800 && cp <= 0xdfff))) ||
                   (k == 3 && (cp < 0x10000 || cp > 0x10ffff))))
            ok = 0;
        if (!ok)
            return sl_fail(d, kind, path, line, NULL, "byte 0x%02x at column %zu is not UTF-8 text", c,
                           i - col0 + 1);
        i += k + 1;
    }
    return SL_OK;
}

/* ---- the parse: events into nodes ---- */

enum build_err { B_OK, B_SYNTAX, B_DEPTH, B_ALIAS, B_NODES, B_NOMEM };

struct build {
    struct sl_yaml_pos *t;
    int origin;
    struct sl_ynode *root;
    struct sl_ynode *open[SL_YAML_MAX_DEPTH];   /* the containers open now */
    int depth;
    int done;              /* the first document's root is complete: later ones are only checked */
    /* the error */
    enum build_err err;
    int line;
    char key[96];          /* where: a key path, "" if none */
    char what[128];        /* libyaml's problem, or the alias's anchor */
};

/* The path a node about to be added to the open container p would have. */
static void pending_path(const struct build *b, char *buf, size_t n)
{
    buf[0] = '\0';
    if (!b->depth)
        return;
    const struct sl_ynode *p = b->open[b->depth - 1];
    size_t k = sl_ynode_path(p, buf, n);
    if (p->kind == SL_YSEQ) {
        snprintf(buf + k, n - k, "[%u]", p->n);
    } else if (p->n && p->kid[2 * p->n - 1] == NULL) {
        /* a key read, its value next */
        const char *kt = p->kid[2 * p->n - 2]->text;
        snprintf(buf + k, n - k, "%s%s", k ? "." : "", kt ? kt : "?");
    }
}

/* Add node to the open container (or make it the root). */
static int attach(struct build *b, struct sl_ynode *n)
{
    if (!b->depth) {   /* a later document's root is checked, not kept */
        if (!b->root)
            b->root = n;
        return 1;
    }
    struct sl_ynode *p = b->open[b->depth - 1];
    n->parent = p;
    if (p->kind == SL_YSEQ) {
        if (!slot_push(p, p->n, n))
            return 0;
        n->index = p->n++;
        return 1;
    }
    if (p->n && p->kid[2 * p->n - 1] == NULL) {   /* the value of the last key */
        p->kid[2 * p->n - 1] = n;
        n->key = p->kid[2 * p->n - 2];
        n->index = p->n - 1;
        return 1;
    }
    /* a key: its value's slot stays NULL until the value comes */
    if (!slot_push(p, 2 * p->n, n) || !slot_push(p, 2 * p->n + 1, NULL))
        return 0;
    n->index = p->n++;
    return 1;
}

/* The top-level key the open containers are under ("" if none). */
static void top_key(const struct build *b, char *buf, size_t n)
{
    buf[0] = '\0';
    if (b->depth && b->open[0]->kind == SL_YMAP && b->open[0]->n) {
        const struct sl_ynode *k = b->open[0]->kid[2 * b->open[0]->n - 2];
        if (k && k->text)
            snprintf(buf, n, "%s", k->text);
    }
}

/* Where a syntax error is named: the last node read in the innermost open
 * container (the key path and line an event-driven loader would be at),
 * else the container itself. */
static void syntax_place(struct build *b, const yaml_parser_t *p)
{
    b->line = (int)p->problem_mark.line + 1;
    b->key[0] = '\0';
    if (!b->depth)
        return;
    const struct sl_ynode *c = b->open[b->depth - 1];
    if (c->kind == SL_YMAP && c->n) {
        /* the last key, at its value's line once the value is read */
        const struct sl_ynode *k = c->kid[2 * c->n - 2], *v = c->kid[2 * c->n - 1];
        size_t n = sl_ynode_path(c, b->key, sizeof b->key);
        snprintf(b->key + n, sizeof b->key - n, "%s%s", n ? "." : "", k->text ? k->text : "?");
        b->line = v ? v->line : k->line;
        return;
    }
    const struct sl_ynode *at = c->kind == SL_YSEQ && c->n ? c->kid[c->n - 1] : c;
    sl_ynode_path(at, b->key, sizeof b->key);
    b->line = at->line;
}

static void build_run(struct build *b, const unsigned char *text, size_t len)
{
    yaml_parser_t p;
    if (!yaml_parser_initialize(&p)) {
        b->err = B_NOMEM;
        return;
    }
    yaml_parser_set_input_string(&p, text, len);
    for (;;) {
        yaml_event_t ev;
        if (!yaml_parser_parse(&p, &ev)) {
            if (!b->done) {   /* past the first document libcyaml read nothing: neither do we */
                b->err = p.error == YAML_MEMORY_ERROR ? B_NOMEM : B_SYNTAX;
                snprintf(b->what, sizeof b->what, "%s", p.problem ? p.problem : "syntax error");
                syntax_place(b, &p);
            }
            break;
        }
        yaml_event_type_t et = ev.type;
        int line = (int)ev.start_mark.line + 1, col = (int)ev.start_mark.column + 1;
        int start = et == YAML_MAPPING_START_EVENT || et == YAML_SEQUENCE_START_EVENT;
        int end = et == YAML_MAPPING_END_EVENT || et == YAML_SEQUENCE_END_EVENT;
        if (et == YAML_ALIAS_EVENT) {
            b->err = B_ALIAS;
            b->line = line;
            pending_path(b, b->key, sizeof b->key);
            snprintf(b->what, sizeof b->what, "%.31s", (const char *)ev.data.alias.anchor);
            yaml_event_delete(&ev);
            break;
        }
        if (start || et == YAML_SCALAR_EVENT) {
            if (start && b->depth == SL_YAML_MAX_DEPTH) {
                b->err = B_DEPTH;
                b->line = line;
                top_key(b, b->key, sizeof b->key);
                yaml_event_delete(&ev);
                break;
            }
            struct sl_ynode *n = node_new(b->t, et == YAML_SCALAR_EVENT ? SL_YSCALAR
                                                : et == YAML_MAPPING_START_EVENT ? SL_YMAP : SL_YSEQ,
                                          line, col, b->origin);
            if (!n) {
                b->err = b->t->nodes >= b->t->max_nodes ? B_NODES : B_NOMEM;
                b->line = line;
                pending_path(b, b->key, sizeof b->key);
                yaml_event_delete(&ev);
                break;
            }
            if (et == YAML_SCALAR_EVENT &&
                !(n->text = text_new(b->t, (const char *)ev.data.scalar.value, ev.data.scalar.length))) {
                b->err = B_NOMEM;
                yaml_event_delete(&ev);
                break;
            }
            if (et == YAML_SCALAR_EVENT) {
                n->quoted = ev.data.scalar.style != YAML_PLAIN_SCALAR_STYLE &&
                            ev.data.scalar.style != YAML_ANY_SCALAR_STYLE;
            }
            if (!attach(b, n)) {
                b->err = B_NOMEM;
                yaml_event_delete(&ev);
                break;
            }
            if (start)
                b->open[b->depth++] = n;
            else if (!b->depth)
                b->done = 1;
        } else if (end) {
            if (b->depth)
                b->depth--;
            if (!b->depth)
                b->done = 1;
        }
        int stream_end = et == YAML_STREAM_END_EVENT;
        yaml_event_delete(&ev);
        if (stream_end)
            break;
    }
    yaml_parser_delete(&p);
}

static struct sl_yaml_pos *tree_new(size_t max_nodes)
{
    struct sl_yaml_pos *t = calloc(1, sizeof *t);
    if (t)
        t->max_nodes = max_nodes;
    return t;
}

static int src_add(struct sl_yaml_pos *t, const char *s)
{
    if (t->nsrc > SRC_MAX)
        return -1;
    if (!(t->src[t->nsrc] = strdup(s)))
        return -1;
    return t->nsrc++;
}

enum sl_err sl_ytree_read(const char *path, size_t max_bytes, enum sl_err kind, struct sl_yaml_pos **out,
                          struct sl_diag *d)
{
    *out = NULL;
    unsigned char *text;
    size_t len;
    enum sl_err e = read_text(path, max_bytes, &text, &len, kind, d);
    if (!e)
        e = check_text(path, text, len, kind, d);
    if (e) {
        free(text);
        return e;
    }
    /* a node takes at least two bytes of YAML ("1,"), so a file within its
     * limit could hold max_bytes / 2 of them; a quarter of that keeps a
     * hostile file's tree (about 70 bytes a node: 60 MB of "[1,1,...]"
     * takes 0.6 GB and 3 s to refuse) within 10 times its size, and is
     * above what the files shadowlab writes or ships hold at their size
     * (6 bytes or more a node: ci.yaml's baseline, the scenes) */
    size_t max_nodes = max_bytes / 8 > 65536 ? max_bytes / 8 : 65536;
    struct sl_yaml_pos *t = tree_new(max_nodes);
    if (!t || src_add(t, path) != 0) {
        free(text);
        sl_ytree_free(t);
        return sl_fail(d, SL_E_NOMEM, path, 0, NULL, "the YAML tree");
    }
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < len; i++)
        h = (h ^ text[i]) * 1099511628211ull;
    t->hash = h;
    struct build b;
    memset(&b, 0, sizeof b);
    b.t = t;
    build_run(&b, text, len);
    free(text);
    const char *key = b.key[0] ? b.key : NULL;
    switch (b.err) {
    case B_OK:
        t->root = b.root;
        *out = t;
        return SL_OK;
    case B_SYNTAX:
        e = sl_fail(d, kind, path, b.line, key, "libyaml: %s", b.what);
        break;
    case B_DEPTH:
        e = sl_fail(d, kind, path, b.line, key, "nested more than %d levels deep: refused before it is read further",
                    SL_YAML_MAX_DEPTH);
        break;
    case B_ALIAS:
        e = sl_fail(d, kind, path, b.line, key, "an alias (*%s): YAML anchors and aliases are not read, write the "
                    "value out (an alias can expand a small file into gigabytes)", b.what);
        break;
    case B_NODES:
        e = sl_fail(d, kind, path, b.line, key, "more than %zu YAML values: at most %zu are read for this kind "
                    "of file", t->max_nodes, t->max_nodes);
        break;
    case B_NOMEM:
        e = sl_fail(d, SL_E_NOMEM, path, b.line, key, "the YAML tree");
        break;
    }
    sl_ytree_free(t);
    return e;
}

enum sl_err sl_ytree_value(struct sl_yaml_pos *t, const char *text, const char *source, const char *key,
                           struct sl_ynode **out, struct sl_diag *d)
{
    *out = NULL;
    int origin = src_add(t, source);
    if (origin < 0)
        return sl_fail(d, SL_E_NOMEM, source, 0, key, "the -D value");
    struct build b;
    memset(&b, 0, sizeof b);
    b.t = t;
    b.origin = origin;
    build_run(&b, (const unsigned char *)text, strlen(text));
    switch (b.err) {
    case B_OK:
        if (b.root) {
            *out = b.root;
            return SL_OK;
        }
        /* nothing but blanks or comments */
        return sl_fail(d, SL_E_CONFIG, source, 0, key, "the value '%s' is not YAML", text);
    case B_SYNTAX:
        return sl_fail(d, SL_E_CONFIG, source, 0, key, "the value '%s' is not YAML", text);
    case B_DEPTH:
        return sl_fail(d, SL_E_CONFIG, source, 0, key, "the value is nested more than %d levels deep",
                       SL_YAML_MAX_DEPTH);
    case B_ALIAS:
        return sl_fail(d, SL_E_CONFIG, source, 0, key, "the value holds an alias (*%s): YAML anchors and "
                       "aliases are not read, write the value out", b.what);
    case B_NODES:
    case B_NOMEM:
        break;
    }
    return sl_fail(d, SL_E_NOMEM, source, 0, key, "the -D value");
}

/* ---- queries ---- */

const char *sl_ytree_file(const struct sl_yaml_pos *t) { return t->src[0]; }
struct sl_ynode *sl_ytree_root(const struct sl_yaml_pos *t) { return t->root; }
unsigned long long sl_ytree_hash(const struct sl_yaml_pos *t) { return t->hash; }

struct sl_ynode *sl_ynode_get(const struct sl_ynode *map, const char *key)
{
    if (!map || map->kind != SL_YMAP)
        return NULL;
    for (unsigned i = 0; i < map->n; i++) {
        const struct sl_ynode *k = map->kid[2 * i];
        if (k && k->text && strcmp(k->text, key) == 0)
            return map->kid[2 * i + 1];
    }
    return NULL;
}

size_t sl_ynode_path(const struct sl_ynode *n, char *buf, size_t size)
{
    if (!size)
        return 0;
    buf[0] = '\0';
    if (!n || !n->parent)
        return 0;
    size_t k = sl_ynode_path(n->parent, buf, size);
    if (k >= size)
        k = size - 1;
    int w;
    const struct sl_ynode *name = n->key ? n->key : n;   /* a key names itself */
    if (n->parent->kind == SL_YSEQ)
        w = snprintf(buf + k, size - k, "[%u]", n->index);
    else
        w = snprintf(buf + k, size - k, "%s%s", k ? "." : "", name->text ? name->text : "?");
    return w < 0 ? k : k + (size_t)w < size ? k + (size_t)w : size - 1;
}

const char *sl_ynode_source(const struct sl_yaml_pos *t, const struct sl_ynode *n)
{
    return n && n->origin < t->nsrc ? t->src[n->origin] : t->src[0];
}

int sl_ynode_line(const struct sl_ynode *n)
{
    if (!n || n->origin)
        return 0;
    return n->key ? n->key->line : n->line;
}

/* One step of a key path: name, then an optional [index] (-1 if none);
 * returns the rest after the step's '.', or NULL if malformed (msg set). */
static const char *path_step(const char *p, char *name, size_t nname, long *idx, char *msg, size_t nmsg)
{
    size_t k = strcspn(p, ".[");
    if (k == 0 || k >= nname) {
        snprintf(msg, nmsg, "not a key path (name.name[index])");
        return NULL;
    }
    memcpy(name, p, k);
    name[k] = '\0';
    p += k;
    *idx = -1;
    if (*p == '[') {
        char *end;
        long v = strtol(p + 1, &end, 10);
        if (end == p + 1 || *end != ']' || v < 0 || v > 1000) {
            snprintf(msg, nmsg, "an index is [N], N >= 0");
            return NULL;
        }
        *idx = v;
        p = end + 1;
    }
    if (*p == '.')
        return p + 1;
    if (*p) {
        snprintf(msg, nmsg, "not a key path (name.name[index])");
        return NULL;
    }
    return p;
}

struct sl_ynode *sl_ytree_find(const struct sl_yaml_pos *t, const char *path)
{
    struct sl_ynode *n = t->root;
    const char *p = path;
    char msg[8];
    while (n && *p) {
        char name[128];
        long idx;
        if (!(p = path_step(p, name, sizeof name, &idx, msg, sizeof msg)))
            return NULL;
        n = sl_ynode_get(n, name);
        if (n && idx >= 0)
            n = n->kind == SL_YSEQ && (unsigned long)idx < n->n ? n->kid[idx] : NULL;
    }
    return n;
}

/* ---- -D: grafting ---- */

static struct sl_ynode *key_new(struct sl_yaml_pos *t, const char *name, int origin)
{
    struct sl_ynode *k = node_new(t, SL_YSCALAR, 0, 0, origin);
    if (k && !(k->text = text_new(t, name, strlen(name))))
        return NULL;
    return k;
}

int sl_ytree_set(struct sl_yaml_pos *t, const char *path, struct sl_ynode *val, char *msg, size_t nmsg)
{
    struct sl_ynode *node = t->root;
    const char *p = path;
    while (*p) {
        char name[64];
        long idx;
        if (!(p = path_step(p, name, sizeof name, &idx, msg, nmsg)))
            return 0;
        if (!node || node->kind != SL_YMAP) {
            snprintf(msg, nmsg, "'%s' is inside a value that is not a mapping", name);
            return 0;
        }
        int last = !*p;
        int hit = -1;   /* the last pair of that key, as a later pair overrides an earlier one */
        for (unsigned i = 0; i < node->n; i++)
            if (node->kid[2 * i]->text && strcmp(node->kid[2 * i]->text, name) == 0)
                hit = (int)i;
        if (hit < 0) {
            if (idx >= 0) {
                snprintf(msg, nmsg, "the config has no '%s' list to index", name);
                return 0;
            }
            /* a new key: the schema says later whether it exists */
            struct sl_ynode *k = key_new(t, name, val->origin);
            struct sl_ynode *v = last ? val : node_new(t, SL_YMAP, 0, 0, val->origin);
            if (!k || !v || !slot_push(node, 2 * node->n, k) || !slot_push(node, 2 * node->n + 1, v)) {
                snprintf(msg, nmsg, "out of memory");
                return 0;
            }
            k->parent = v->parent = node;
            v->key = k;
            k->index = v->index = node->n++;
            node = v;
            continue;
        }
        struct sl_ynode *cur = node->kid[2 * hit + 1];
        if (idx < 0) {
            if (last) {
                node->kid[2 * hit + 1] = val;
                val->parent = node;
                val->key = node->kid[2 * hit];
                val->index = (unsigned)hit;
                val->taken = 0;
            }
            node = node->kid[2 * hit + 1];
            continue;
        }
        if (cur->kind != SL_YSEQ) {
            snprintf(msg, nmsg, "'%s' is not a list", name);
            return 0;
        }
        unsigned count = cur->n;
        if ((unsigned long)idx > count || ((unsigned long)idx == count && !last)) {
            snprintf(msg, nmsg, "'%s' has %u entr%s (an index past them adds one only as the last step)", name,
                     count, count == 1 ? "y" : "ies");
            return 0;
        }
        if ((unsigned long)idx == count) {
            if (!slot_push(cur, cur->n, val)) {
                snprintf(msg, nmsg, "out of memory");
                return 0;
            }
            cur->n++;
        } else if (last) {
            cur->kid[idx] = val;
        } else {
            node = cur->kid[idx];
            continue;
        }
        val->parent = cur;
        val->key = NULL;
        val->index = (unsigned)idx;
        node = val;
    }
    return 1;
}
