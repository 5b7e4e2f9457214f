/* ytree::* — a YAML file read once into a positioned node tree: each node's
 * line, column, key path and text; the limits refused while reading; -D
 * values grafted into the tree (their errors naming the -D value and key);
 * the tree bound to C structs by a libcyaml schema, with libcyaml's checks
 * and our whole-number check. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include "sl_test.h"
#include "suggest.h"
#include "util.h"
#include "yamlfile.h"
#include "ytree.h"

static void write_file(char *path, const char *text)
{
    strcpy(path, "/tmp/shadowlab-ytree-XXXXXX.yaml");
    int fd = mkstemps(path, 5);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fputs(text, f);
    fclose(f);
}

static const char *doc =
    "# a comment\n"                        /* 1 */
    "name: study\n"                        /* 2 */
    "map_sizes: [512, \"1024\"]\n"         /* 3 */
    "methods:\n"                           /* 4 */
    "  - method: nsm\n"                    /* 5 */
    "    bias: 0.5\n"                      /* 6 */
    "  - {method: pcf, kernel: [1, 3]}\n"; /* 7 */

static void ytree_positions(void **st)
{
    (void)st;
    char path[64];
    write_file(path, doc);
    struct sl_yaml_pos *t;
    struct sl_diag d;
    assert_int_equal(sl_ytree_read(path, 1 << 20, SL_E_CONFIG, &t, &d), SL_OK);
    unsigned long long h = 0;
    assert_int_equal(sl_hash_file(path, &h, &d), SL_OK);
    /* read once: the file can go, every answer comes from the tree */
    remove(path);
    assert_true(sl_ytree_hash(t) == h);
    assert_string_equal(sl_ytree_file(t), path);
    struct sl_ynode *root = sl_ytree_root(t);
    assert_int_equal(root->kind, SL_YMAP);
    assert_int_equal(root->n, 3);
    struct sl_ynode *n = sl_ytree_find(t, "map_sizes[1]");
    assert_non_null(n);
    assert_int_equal(n->kind, SL_YSCALAR);
    assert_string_equal(n->text, "1024");
    assert_int_equal(n->quoted, 1);
    assert_int_equal(n->line, 3);
    assert_int_equal(n->col, 18);
    assert_int_equal(sl_ytree_find(t, "map_sizes[0]")->quoted, 0);
    char p[96];
    n = sl_ytree_find(t, "methods[1].kernel[1]");
    assert_non_null(n);
    assert_string_equal(n->text, "3");
    assert_int_equal(n->line, 7);
    assert_int_equal(n->col, 31);
    sl_ynode_path(n, p, sizeof p);
    assert_string_equal(p, "methods[1].kernel[1]");
    /* a mapping value's line is its key's; a block entry's its own */
    n = sl_ytree_find(t, "methods");
    assert_int_equal(n->kind, SL_YSEQ);
    assert_int_equal(n->line, 5);
    assert_int_equal(sl_ynode_line(n), 4);
    assert_int_equal(sl_yaml_line(t, "methods"), 4);
    assert_int_equal(sl_yaml_line(t, "methods[0]"), 5);
    assert_int_equal(sl_yaml_line(t, "methods[0].bias"), 6);
    assert_int_equal(sl_yaml_line(t, "methods[1].kernel"), 7);
    assert_int_equal(sl_yaml_line(t, "methods[2]"), 0);
    assert_int_equal(sl_yaml_line(t, "nope"), 0);
    assert_int_equal(sl_yaml_line(t, ""), 0);
    assert_string_equal(sl_ynode_get(sl_ytree_find(t, "methods[0]"), "method")->text, "nsm");
    assert_string_equal(sl_ynode_source(t, sl_ytree_find(t, "name")), path);
    sl_ytree_free(t);
}

/* Each limit refused while the file is read, at its line, naming its key. */
static void ytree_refusals(void **st)
{
    (void)st;
    static const struct { const char *text; int line; const char *key, *msg; } bad[] = {
        {"a: &x [1]\nb: *x\n", 2, "b", "an alias (*x)"},
        {"a:\n  - [1, 2]\n  - *y\n", 3, "a[1]", "an alias (*y)"},
        {"a: 1\n---\nb: *z\n", 3, "b", "an alias (*z)"},   /* a later document is checked too */
        {"a: 1\nb: [1, 2\nc: 3\n", 2, "b[1]", "libyaml: did not find expected ',' or ']'"},
        {"a: 1\nb: 2\n\xff\n", 3, NULL, "byte 0xff at column 1 is not UTF-8 text"},
        {"a: 1\nb: x\x01y\n", 2, NULL, "control character"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char path[64];
        write_file(path, bad[i].text);
        struct sl_yaml_pos *t = (struct sl_yaml_pos *)&t;
        struct sl_diag d;
        memset(&d, 0, sizeof d);
        assert_int_equal(sl_ytree_read(path, 1 << 20, SL_E_SCENE, &t, &d), SL_E_SCENE);
        remove(path);
        assert_null(t);
        assert_string_equal(d.file, path);
        assert_int_equal(d.line, bad[i].line);
        assert_string_equal(d.key, bad[i].key ? bad[i].key : "");
        assert_non_null(strstr(d.msg, bad[i].msg));
    }
    /* nesting: refused where it passes the limit, naming the top-level key */
    char text[400], path[64];
    int k = snprintf(text, sizeof text, "a: 1\ndeep:\n  ");
    for (int i = 0; i < SL_YAML_MAX_DEPTH; i++)
        text[k++] = '[';
    text[k] = '\0';
    write_file(path, text);
    struct sl_yaml_pos *t;
    struct sl_diag d;
    assert_int_equal(sl_ytree_read(path, 1 << 20, SL_E_CONFIG, &t, &d), SL_E_CONFIG);
    assert_int_equal(d.line, 3);
    assert_string_equal(d.key, "deep");
    assert_non_null(strstr(d.msg, "nested more than 64 levels"));
    remove(path);
    /* 63 more levels under the top mapping are fine */
    text[k - 1] = '\0';
    strcat(text, "1");
    for (int i = 0; i < SL_YAML_MAX_DEPTH - 1; i++)
        strcat(text, "]");
    write_file(path, text);
    assert_int_equal(sl_ytree_read(path, 1 << 20, SL_E_CONFIG, &t, &d), SL_OK);
    sl_ytree_free(t);
    remove(path);
    /* over the byte limit: refused unread */
    write_file(path, "a: 12345678\n");
    assert_int_equal(sl_ytree_read(path, 8, SL_E_CONFIG, &t, &d), SL_E_CONFIG);
    assert_non_null(strstr(d.msg, "file of 12 bytes"));
    remove(path);
    /* empty: a tree without root */
    write_file(path, "# nothing\n");
    assert_int_equal(sl_ytree_read(path, 1 << 20, SL_E_CONFIG, &t, &d), SL_OK);
    assert_null(sl_ytree_root(t));
    sl_ytree_free(t);
    remove(path);
}

/* -D: a value parsed once into nodes whose origin is the override, grafted
 * at its path: replacing, creating a key (and its middle mappings),
 * appending to a list; a path that cannot be set says why. */
static void ytree_overrides(void **st)
{
    (void)st;
    char path[64];
    write_file(path, doc);
    struct sl_yaml_pos *t;
    struct sl_diag d;
    assert_int_equal(sl_ytree_read(path, 1 << 20, SL_E_CONFIG, &t, &d), SL_OK);
    remove(path);
    char msg[300], p[96];
    struct sl_ynode *v;
    /* replace a scalar */
    assert_int_equal(sl_ytree_value(t, "other", "-D name=other", "name", &v, &d), SL_OK);
    assert_int_equal(sl_ytree_set(t, "name", v, msg, sizeof msg), 1);
    assert_string_equal(sl_ytree_find(t, "name")->text, "other");
    assert_string_equal(sl_ynode_source(t, sl_ytree_find(t, "name")), "-D name=other");
    assert_int_equal(sl_yaml_line(t, "name"), 0);   /* no line of the file */
    assert_int_equal(sl_yaml_line(t, "map_sizes"), 3);
    /* create a key and the mapping above it */
    assert_int_equal(sl_ytree_value(t, "{runs: 5}", "-D repetitions.inner={runs: 5}", "repetitions.inner", &v, &d),
                     SL_OK);
    assert_int_equal(sl_ytree_set(t, "repetitions.inner", v, msg, sizeof msg), 1);
    struct sl_ynode *n = sl_ytree_find(t, "repetitions.inner.runs");
    assert_non_null(n);
    assert_string_equal(n->text, "5");
    assert_int_equal(n->origin, 2);
    sl_ynode_path(n, p, sizeof p);
    assert_string_equal(p, "repetitions.inner.runs");
    assert_int_equal(sl_ytree_root(t)->n, 4);
    /* replace a list entry's key, then append an entry */
    assert_int_equal(sl_ytree_value(t, "[0.1, 0.2]", "-D methods[0].bias=[0.1, 0.2]", "methods[0].bias", &v, &d),
                     SL_OK);
    assert_int_equal(sl_ytree_set(t, "methods[0].bias", v, msg, sizeof msg), 1);
    assert_string_equal(sl_ytree_find(t, "methods[0].bias[1]")->text, "0.2");
    assert_int_equal(sl_ytree_value(t, "{method: csm}", "-D methods[2]={method: csm}", "methods[2]", &v, &d), SL_OK);
    assert_int_equal(sl_ytree_set(t, "methods[2]", v, msg, sizeof msg), 1);
    assert_int_equal(sl_ytree_find(t, "methods")->n, 3);
    assert_string_equal(sl_ytree_find(t, "methods[2].method")->text, "csm");
    /* paths that cannot be set */
    static const struct { const char *path, *msg; } bad[] = {
        {"methods[9].bias", "'methods' has 3 entries (an index past them adds one only as the last step)"},
        {"methods[3].bias", "'methods' has 3 entries"},
        {"name[0]", "'name' is not a list"},
        {"nolist[0]", "the config has no 'nolist' list to index"},
        {"name.sub", "'sub' is inside a value that is not a mapping"},
        {"methods[x]", "an index is [N], N >= 0"},
        {"a..b", "not a key path"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(sl_ytree_value(t, "1", "-D x=1", bad[i].path, &v, &d), SL_OK);
        assert_int_equal(sl_ytree_set(t, bad[i].path, v, msg, sizeof msg), 0);
        assert_non_null(strstr(msg, bad[i].msg));
    }
    /* values that are not read: named by the -D value and its key */
    static const struct { const char *text, *msg; } badv[] = {
        {"[1", "the value '[1' is not YAML"},
        {"", "the value '' is not YAML"},
        {"[&a 1, *a]", "alias (*a)"},
    };
    for (size_t i = 0; i < sizeof badv / sizeof badv[0]; i++) {
        memset(&d, 0, sizeof d);
        assert_int_equal(sl_ytree_value(t, badv[i].text, "-D seed=...", "seed", &v, &d), SL_E_CONFIG);
        assert_string_equal(d.file, "-D seed=...");
        assert_int_equal(d.line, 0);
        assert_string_equal(d.key, "seed");
        assert_non_null(strstr(d.msg, badv[i].msg));
    }
    sl_ytree_free(t);
}

/* Binding: the structs a libcyaml schema declares, filled from the tree;
 * errors name the node's line and key, or the -D value it came from. */
struct b_entry { unsigned *size; char *label; };
struct b_file {
    char *name;
    float scale;
    bool *on;
    struct b_entry *items; unsigned items_count;
};
static const cyaml_schema_field_t b_entry_fields[] = {
    CYAML_FIELD_UINT_PTR("size", CYAML_FLAG_POINTER, struct b_entry, size),
    CYAML_FIELD_STRING_PTR("label", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct b_entry, label, 1, 7),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t b_entry_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_DEFAULT, struct b_entry, b_entry_fields),
};
static const cyaml_schema_field_t b_fields[] = {
    CYAML_FIELD_STRING_PTR("name", CYAML_FLAG_POINTER, struct b_file, name, 1, 63),
    CYAML_FIELD_FLOAT("scale", CYAML_FLAG_OPTIONAL, struct b_file, scale),
    CYAML_FIELD_BOOL_PTR("on", CYAML_FLAG_POINTER | CYAML_FLAG_OPTIONAL, struct b_file, on),
    CYAML_FIELD_SEQUENCE("items", CYAML_FLAG_POINTER, struct b_file, items, &b_entry_schema, 1, 3),
    CYAML_FIELD_END,
};
static const cyaml_schema_value_t b_schema = {
    CYAML_VALUE_MAPPING(CYAML_FLAG_POINTER, struct b_file, b_fields),
};

static enum sl_err bind_text(const char *text, struct b_file **out, struct sl_diag *d)
{
    char path[64];
    write_file(path, text);
    struct sl_yaml_pos *t;
    enum sl_err e = sl_yaml_load(path, &b_schema, (void **)out, &t, 1 << 20, SL_E_SCENE, d);
    remove(path);
    sl_ytree_free(t);
    return e;
}

static void ytree_bind(void **st)
{
    (void)st;
    struct b_file *f;
    struct sl_diag d;
    assert_int_equal(bind_text("name: x\nscale: 2.5\non: no\nitems:\n  - {size: 4, label: ab}\n  - size: +7\n", &f,
                               &d),
                     SL_OK);
    assert_string_equal(f->name, "x");
    assert_true(f->scale == 2.5f);
    assert_false(*f->on);
    assert_int_equal(f->items_count, 2);
    assert_int_equal(*f->items[0].size, 4);
    assert_string_equal(f->items[0].label, "ab");
    assert_int_equal(*f->items[1].size, 7);
    assert_null(f->items[1].label);
    sl_yaml_free(&b_schema, f, NULL);
    static const struct { const char *text; int line; const char *key, *msg; } bad[] = {
        {"name: x\nitems: [{size: 1}]\nextra: 1\n", 3, "extra", "unknown key 'extra'"},
        {"name: x\nitems: [{size: 1}]\nscael: 1\n", 3, "scael", "unknown key 'scael' (did you mean 'scale'?)"},
        {"name: x\nitems: [{sise: 1}]\n", 2, "items[0].sise", "unknown key 'sise' (did you mean 'size'?)"},
        {"name: x\nitems: big\n", 2, "items", "expected a list ([a, b] or '- a' lines), got 'big'"},
        {"name: x\nitems:\n  - {size: 1}\n  - {label: a}\n", 4, "items[1].size", "missing required key"},
        {"items: [{size: 1}]\n", 0, "name", "missing required key"},
        {"name: x\nitems: [{size: 1}, {size: 2}, {size: 3},\n  {size: 4}]\n", 3, "items",
         "more than 3 entries: at most 3 are allowed"},
        {"name: x\nitems: []\n", 2, "items", "expected a list of at least 1 entry, got 0"},
        {"name: x\nitems: [{size: 7.9}]\n", 2, "items[0].size", "'7.9' is not a whole number"},
        {"name: x\nitems: [{size: 1e3}]\nscale: 1\n", 2, "items[0].size", "'1e3' is not a whole number"},
        {"name: x\nitems: [{size: -1}]\n", 2, "items[0].size", "expected a whole number, 0 or more, got '-1'"},
        {"name: x\nitems: [{size: big}]\n", 2, "items[0].size", "expected a whole number, 0 or more, got 'big'"},
        {"name: x\nitems: [{size: 1, label: toolongtext}]\n", 2, "items[0].label", "expected a text of at most 7 characters, got 'toolongtext' (11)"},
        {"name: x\nscale: wide\nitems: [{size: 1}]\n", 2, "scale", "expected a number, got 'wide'"},
        {"name: [x]\nitems: [{size: 1}]\n", 1, "name", "expected a word or a quoted text, got a list"},
        {"name: x\nname: y\nitems: [{size: 1}]\n", 2, "name", "the key 'name' is given twice"},
        {"- name: x\n", 1, NULL, "the file is a sequence"},
        {"name: x\nitems:\n  - ? [a]\n    : 1\n", 3, "items[0]", "a key is a plain word"},
        {"", 0, NULL, "empty file"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        memset(&d, 0, sizeof d);
        f = (struct b_file *)&f;
        assert_int_equal(bind_text(bad[i].text, &f, &d), SL_E_SCENE);
        assert_null(f);
        assert_int_equal(d.line, bad[i].line);
        assert_string_equal(d.key, bad[i].key ? bad[i].key : "");
        assert_non_null(strstr(d.msg, bad[i].msg));
    }
    /* a value grafted from -D: its errors name the override, not a line */
    char path[64];
    write_file(path, "name: x\nitems: [{size: 1}]\n");
    struct sl_yaml_pos *t;
    assert_int_equal(sl_ytree_read(path, 1 << 20, SL_E_CONFIG, &t, &d), SL_OK);
    remove(path);
    struct sl_ynode *v;
    char msg[200];
    assert_int_equal(sl_ytree_value(t, "2.5", "-D items[0].size=2.5", "items[0].size", &v, &d), SL_OK);
    assert_int_equal(sl_ytree_set(t, "items[0].size", v, msg, sizeof msg), 1);
    assert_int_equal(sl_yaml_bind(t, &b_schema, (void **)&f, SL_E_CONFIG, &d), SL_E_CONFIG);
    assert_string_equal(d.file, "-D items[0].size=2.5");
    assert_int_equal(d.line, 0);
    assert_string_equal(d.key, "items[0].size");
    assert_non_null(strstr(d.msg, "'2.5' is not a whole number"));
    /* a taken value is out of the schema's view */
    assert_int_equal(sl_ytree_value(t, "3", "-D items[0].size=3", "items[0].size", &v, &d), SL_OK);
    assert_int_equal(sl_ytree_set(t, "items[0].size", v, msg, sizeof msg), 1);
    assert_int_equal(sl_ytree_value(t, "[1, 2]", "-D sweep=[1, 2]", "sweep", &v, &d), SL_OK);
    assert_int_equal(sl_ytree_set(t, "sweep", v, msg, sizeof msg), 1);
    assert_int_equal(sl_yaml_bind(t, &b_schema, (void **)&f, SL_E_CONFIG, &d), SL_E_CONFIG);
    assert_string_equal(d.file, "-D sweep=[1, 2]");
    assert_string_equal(d.key, "sweep");
    v->taken = 1;
    assert_int_equal(sl_yaml_bind(t, &b_schema, (void **)&f, SL_E_CONFIG, &d), SL_OK);
    assert_int_equal(*f->items[0].size, 3);
    sl_yaml_free(&b_schema, f, t);
}

/* "did you mean" (base/suggest.h): the distance, the threshold and ties */
static void ytree_suggest(void **state)
{
    (void)state;
    assert_int_equal(sl_edit_distance("", ""), 0);
    assert_int_equal(sl_edit_distance("nsm", "nsm"), 0);
    assert_int_equal(sl_edit_distance("NSM", "nsm"), 0);        /* case ignored */
    assert_int_equal(sl_edit_distance("map_size", "map_sizes"), 1);
    assert_int_equal(sl_edit_distance("scael", "scale"), 1);    /* a swap is one edit */
    assert_int_equal(sl_edit_distance("kitten", "sitting"), 3);
    assert_int_equal(sl_edit_distance("", "abc"), 3);
    char hint[96];
    struct sl_suggest sg;
    const char *labels[] = {"nsm", "csm", "chain", "texel", NULL};
    sl_suggest_init(&sg, "chian");
    for (int i = 0; labels[i]; i++)
        sl_suggest_add(&sg, labels[i]);
    assert_string_equal(sl_suggest_best(&sg), "chain");
    assert_string_equal(sl_suggest_text(&sg, hint, sizeof hint), " (did you mean 'chain'?)");
    /* "bsm" is one edit from nsm and from csm: a tie names neither */
    sl_suggest_init(&sg, "bsm");
    for (int i = 0; labels[i]; i++)
        sl_suggest_add(&sg, labels[i]);
    assert_null(sl_suggest_best(&sg));
    assert_string_equal(sl_suggest_text(&sg, hint, sizeof hint), "");
    /* too far: "nope" (4 letters allow 1 edit) is 3 edits from nsm, the nearest */
    sl_suggest_init(&sg, "nope");
    for (int i = 0; labels[i]; i++)
        sl_suggest_add(&sg, labels[i]);
    assert_null(sl_suggest_best(&sg));
    /* a member is no typo */
    sl_suggest_init(&sg, "texel");
    for (int i = 0; labels[i]; i++)
        sl_suggest_add(&sg, labels[i]);
    assert_null(sl_suggest_best(&sg));
    /* longer words allow len/3 edits: "neighbors" (9) -> "neighbours" (1 edit), "adjcncy" (7: 2) */
    sl_suggest_init(&sg, "adjcncy");
    sl_suggest_add(&sg, "adjacency");
    sl_suggest_add(&sg, "neighbours");
    assert_string_equal(sl_suggest_best(&sg), "adjacency");
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        SL_CASE(ytree, positions),
        SL_CASE(ytree, refusals),
        SL_CASE(ytree, overrides),
        SL_CASE(ytree, bind),
        SL_CASE(ytree, suggest),
    };
    return sl_run_group(argc, argv, "ytree", tests, NULL, NULL);
}
