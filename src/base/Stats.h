// Summary statistics of measurements, one definition for every report and benchmark.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace frugal {

// The median of the values that are not NaN (NaN when there are none); an even count gives the mean
// of the two middle values.
inline double median(std::vector<double> values) {
    values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return std::isnan(v); }), values.end());
    if (values.empty()) return std::nan("");
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2.0;
}

}  // namespace frugal
