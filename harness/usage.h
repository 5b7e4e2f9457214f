#ifndef SL_USAGE_H
#define SL_USAGE_H
/* usage: the help text of the command line, one string per verb. It is data
 * only: main.c prints it (the only file that prints), this file keeps main.c
 * to the flow of the verbs. */
extern const char sl_usage[];
extern const char sl_usage_run[];
extern const char sl_usage_validate[];
extern const char sl_usage_table[];
extern const char sl_usage_report[];
extern const char sl_usage_check[];
extern const char sl_usage_bench[];
extern const char sl_usage_list[];
extern const char sl_usage_submit[];
extern const char sl_usage_merge[];
extern const char sl_usage_verify[];
extern const char sl_usage_preview[];
#endif
