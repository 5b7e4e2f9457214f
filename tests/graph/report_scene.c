/* build::graph — with the report's compile flags, scene.h must not be found */
#include "scene.h"
int sl_graph_scene;
