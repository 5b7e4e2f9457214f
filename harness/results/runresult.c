/*
 * runresult.c — see runresult.h.
 */
#include "runresult.h"
#include <stdlib.h>
#include <string.h>

void sl_run_result_free(struct sl_run_result *r)
{
    if (!r)
        return;
    free(r->cells);
    memset(r, 0, sizeof *r);
}
