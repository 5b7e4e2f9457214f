/* build::graph — the report's compile flags reach the store's read API */
#include "figrec.h"
#include "motion.h"
#include "report.h"
#include "store.h"
#include "table.h"
int sl_graph_allowed;
