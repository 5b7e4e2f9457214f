/* build::graph — with the report's compile flags, truth.h must not be found */
#include "truth.h"
int sl_graph_truth;
