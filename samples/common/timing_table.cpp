#include "timing_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace cloth_samples {

double percentile(std::vector<double> values, double p) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    return values[static_cast<size_t>(std::lround(p * static_cast<double>(values.size() - 1)))];
}

void print_timing_row(const char* name, const std::vector<double>& ms, double budget_ms, int name_width) {
    const auto overruns = std::count_if(ms.begin(), ms.end(), [&](double v) { return v > budget_ms; });
    std::printf("%-*s %9.3f %9.3f %9.3f %9.3f %9ld\n", name_width, name, percentile(ms, 0.5),
                percentile(ms, 0.95), percentile(ms, 0.99), percentile(ms, 1.0), static_cast<long>(overruns));
}

std::vector<double>* TimingTable::add_row(const std::string& name, bool only_if_ran) {
    rows_.push_back({name, only_if_ran, {}});
    return &rows_.back().ms;
}

void TimingTable::print(const std::string& title, const char* first_column, double budget_ms,
                        int name_width) const {
    std::printf("\n%s, ms (shared machine: noisy); budget %.2f ms\n", title.c_str(), budget_ms);
    std::printf("%-*s %9s %9s %9s %9s %9s\n", name_width, first_column, "p50", "p95", "p99", "max",
                "overruns");
    for (const Row& row : rows_) {
        if (row.only_if_ran && row.ms.empty()) continue;
        print_timing_row(row.name.c_str(), row.ms, budget_ms, name_width);
    }
}

}  // namespace cloth_samples
