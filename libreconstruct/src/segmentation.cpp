#include "reconstruct/contours.h"

namespace contourmesh {}  // namespace contourmesh
