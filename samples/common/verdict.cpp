#include "verdict.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace cloth_samples {

Verdict::Verdict(std::vector<std::string> checks)
    : checks_(std::move(checks)), passed_(checks_.size(), false), required_(checks_.size(), true) {}

void Verdict::add_require_option(CLI::App& app, std::string* list) const {
    std::string names;
    for (const std::string& check : checks_) names += (names.empty() ? "" : ", ") + check;
    app.add_option("--require", *list,
                   "the checks whose failure fails the run, comma-separated, or all: " + names +
                       " (each is reported either way)");
}

bool Verdict::require(const std::string& list) {
    require_ = list;
    std::fill(required_.begin(), required_.end(), list == "all");
    if (list == "all") return true;
    std::stringstream names(list);
    std::string name;
    bool any = false;
    while (std::getline(names, name, ',')) {
        const auto found = std::find(checks_.begin(), checks_.end(), name);
        if (found == checks_.end()) {
            std::fprintf(stderr, "--require: no check named '%s'\n", name.c_str());
            return false;
        }
        required_[found - checks_.begin()] = any = true;
    }
    if (!any) std::fprintf(stderr, "--require: no check named\n");
    return any;
}

size_t Verdict::index(const std::string& check) const {
    return static_cast<size_t>(std::find(checks_.begin(), checks_.end(), check) - checks_.begin());
}

void Verdict::set(const std::string& check, bool passed) {
    const size_t k = index(check);
    if (k < checks_.size()) passed_[k] = passed;
}

void Verdict::print_checks() const {
    std::printf("\n");
    for (size_t k = 0; k < checks_.size(); ++k) {
        std::printf("check %s: %s%s\n", checks_[k].c_str(), passed_[k] ? "pass" : "FAIL",
                    required_[k] ? "" : " (not required)");
    }
}

int Verdict::status() const {
    for (size_t k = 0; k < checks_.size(); ++k) {
        if (required_[k] && !passed_[k]) return 1;
    }
    return output_failed_ ? 1 : 0;
}

int Verdict::finish() const {
    const int result = status();
    if (require_ == "all")
        std::printf("%s\n", result == 0 ? "all checks passed" : "CHECKS FAILED");
    else
        std::printf("%s (%s)\n", result == 0 ? "required checks passed" : "REQUIRED CHECKS FAILED",
                    require_.c_str());
    return result;
}

}  // namespace cloth_samples
