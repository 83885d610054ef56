// The route tables of the distance registry (route.hpp), one function per file of routes:
// each appends its routes, in the order they are tried, to the registry's table.
#pragma once

#include "surfcert/certify/distance/route.hpp"

#include <vector>

namespace surfcert::certify {

void add_degenerate_quadric_routes(std::vector<Route>& table); ///< degenerate_routes.cpp (first)
void add_quadric_pair_routes(std::vector<Route>& table);       ///< quadric_routes.cpp
void add_surface_pair_routes(std::vector<Route>& table);       ///< surface_routes.cpp

} // namespace surfcert::certify
