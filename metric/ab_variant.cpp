#include "metric/ab_variant.h"

namespace meshdev::detail {

int g_ab_variant = 0;

}  // namespace meshdev::detail
