/* build::graph — with the report's compile flags, view.h must not be found */
#include "view.h"
int sl_graph_view;
