// A sample's verdict on its run: each of its checks passed or failed over
// the whole run, the ones --require names deciding it (all by default),
// and any output that could not be written failing it. It ends the run's
// output with "all checks passed" or "CHECKS FAILED" ("required checks
// passed (LIST)" or "REQUIRED CHECKS FAILED (LIST)" under --require) and
// gives the exit status.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace cloth_samples {

class Verdict {
  public:
    // `checks`: the sample's checks, in the order they are reported.
    explicit Verdict(std::vector<std::string> checks);

    // --require LIST into *list: the checks whose failure fails the run,
    // "all" or names separated by commas (each is reported either way).
    void add_require_option(CLI::App& app, std::string* list) const;
    // The checks `list` names decide the run; false, with the error on
    // stderr, if it names no check or one the sample does not have.
    bool require(const std::string& list);

    // Check `check` passed, or failed, over the whole run (a check never
    // set counts as failed).
    void set(const std::string& check, bool passed);
    // An output (trace, video, picture) could not be written.
    void fail_output() { output_failed_ = true; }

    // After a blank line, "check NAME: pass" or "check NAME: FAIL" for each
    // check, " (not required)" after those --require leaves out.
    void print_checks() const;
    // 0 when every required check passed and every output was written, else 1.
    int status() const;
    // Prints the closing line; returns status().
    int finish() const;

  private:
    size_t index(const std::string& check) const;

    std::vector<std::string> checks_;
    std::vector<bool> passed_, required_;
    std::string require_ = "all";
    bool output_failed_ = false;
};

}  // namespace cloth_samples
