#pragma once
// A component's settings read from a scene by its declarations alone (core/parameters.hpp): each
// declared key the scene gives, checked against its kind and range (an InputError naming the file
// and the key), and its default where the scene gives none. A user's component is read as ours.
#include <vector>

#include "core/parameters.hpp"
#include "scene/json_fields.hpp"

namespace corofem {

Parameters read_parameters(JsonFields& f, const std::vector<ParameterSpec>& specs);

}  // namespace corofem
