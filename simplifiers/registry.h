#pragma once
// The list of simplifier backends by name. Every backend is listed whether or not its library was
// built in; a compiled-out one reports available() == false and says why.
#include <memory>
#include <string>
#include <vector>

#include "simplifiers/simplifier.h"

namespace meshdev {

// Registered names in a fixed order (available or not). O(1).
std::vector<std::string> simplifier_names();

// A new backend with default options. Throws InvalidInput listing the known names when `name`
// is not registered.
std::unique_ptr<Simplifier> create_simplifier(const std::string& name);

// One new instance of every registered backend, in simplifier_names() order.
std::vector<std::unique_ptr<Simplifier>> create_all_simplifiers();

}  // namespace meshdev
