// The samples' budget tables: a row of p50 / p95 / p99 / max and the
// frames over budget for one stage's per-frame times, and the table of
// such rows a sample prints after its run.
#pragma once

#include <deque>
#include <string>
#include <vector>

namespace cloth_samples {

// The value at fraction p (0..1) of the sorted values (0 if none).
double percentile(std::vector<double> values, double p);
// Prints "name p50 p95 p99 max overruns" with the name in `name_width` columns.
void print_timing_row(const char* name, const std::vector<double>& ms, double budget_ms, int name_width);

// Rows of per-frame times, ms, printed in the order they were added.
class TimingTable {
  public:
    // A row named `name`: the caller pushes one time per frame into it
    // (the address stays valid). `only_if_ran`: left out of the table
    // while it holds no time (a stage that never ran).
    std::vector<double>* add_row(const std::string& name, bool only_if_ran = false);
    // "\nTITLE, ms (shared machine: noisy); budget B ms", the column
    // heads (`first_column` over the names) and the rows, each name in
    // `name_width` columns.
    void print(const std::string& title, const char* first_column, double budget_ms, int name_width) const;

  private:
    struct Row {
        std::string name;
        bool only_if_ran;
        std::vector<double> ms;
    };
    std::deque<Row> rows_;  // a deque: add_row's pointers outlive later rows
};

}  // namespace cloth_samples
