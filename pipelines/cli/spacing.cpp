// SPDX-License-Identifier: BSD-3-Clause
#include "spacing.h"

#include <contourmesh/smooth/errors.h>

#include <cmath>
#include <exception>
#include <string>
#include <vector>

namespace contourmesh::cli {

// "sx,sy,sz": three comma-separated finite numbers > 0.
Eigen::Vector3d parse_spacing(const std::string& text) {
  const auto fail = [&] {
    throw InvalidInputError("--spacing must be three comma-separated numbers > 0 in mm (e.g. 0.7,0.7,2), got '" + text +
                            "'");
  };
  std::vector<double> values;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      fail();
    }
    // Only surrounding blanks may remain after the number.
    if (item.find_first_not_of(" \t", used) != std::string::npos || !std::isfinite(v) || !(v > 0.0)) fail();
    values.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (values.size() != 3) fail();
  return {values[0], values[1], values[2]};
}

}  // namespace contourmesh::cli
