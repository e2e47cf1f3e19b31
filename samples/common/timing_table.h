// The samples' budget tables: a row of p50 / p95 / p99 / max and the
// frames over budget for one stage's per-frame times.
#pragma once

#include <vector>

namespace cloth_samples {

// The value at fraction p (0..1) of the sorted values (0 if none).
double percentile(std::vector<double> values, double p);
// Prints "name p50 p95 p99 max overruns" with the name in `name_width` columns.
void print_timing_row(const char* name, const std::vector<double>& ms, double budget_ms, int name_width);

}  // namespace cloth_samples
