/*
 * emit.c — the table of emitters (emit.h); each lives in its own file.
 */
#include "emit.h"
#include <string.h>

const struct sl_emitter sl_emitters[] = {
    {"md", sl_emit_md},
    {"csv", sl_emit_csv},
    {"latex", sl_emit_tex},
    {"html", sl_emit_html},
    {"json", sl_emit_json},
    {"term", sl_emit_term},
    {NULL, NULL},
};

sl_emit_fn sl_emit_find(const char *name)
{
    for (int i = 0; name && sl_emitters[i].name; i++)
        if (strcmp(name, sl_emitters[i].name) == 0)
            return sl_emitters[i].emit;
    return NULL;
}
